// Texture wrap modes (shaders/shared/texture.h wrapTexelCoord, compiled as C++): the remainder it
// takes from a float quotient equals the integer one for every coordinate below 2^24 in
// magnitude, for repeat and mirror, and stays a valid texel beyond that. The nearest filter
// (sampleTexture with kTextureNearest) returns the texel a point lies in, unblended. Also: the
// texture table's records, stored as uvec4 words, read back as the host wrote them.
#include <cstdint>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "shared/layouts.h"

// texture.h reads textures through these; the filter tests point them at their own texture.
namespace texture_test_buffers {
const mixtrace::shared::TextureGpu* textures = nullptr;
const uint32_t* texels = nullptr;
}  // namespace texture_test_buffers
#define TEXTURE(i) (::texture_test_buffers::textures[i])
#define TEXEL(i) (::texture_test_buffers::texels[i])
#include "shared/texture.h"

namespace {

using namespace mixtrace::shared;

int repeatReference(int64_t i, int64_t n) { return int(((i % n) + n) % n); }

int mirrorReference(int64_t i, int64_t n) {
  const int64_t period = 2 * n;
  const int64_t m = ((i % period) + period) % period;
  return int(m < n ? m : period - 1 - m);
}

std::vector<int64_t> coordinatesAround(int64_t n) {
  std::vector<int64_t> out;
  for (int64_t i = -3 * n - 5; i <= 3 * n + 5; ++i) out.push_back(i);
  // Near multiples of the periods far out, where a float quotient rounds to the next integer.
  const int64_t limit = (int64_t(1) << 24) - 1;
  for (int64_t k : {int64_t(1000), int64_t(4096), limit / (2 * n), limit / n})
    for (int64_t d = -2; d <= 2; ++d)
      for (int64_t base : {k * n, k * 2 * n})
        if (base + d <= limit) {
          out.push_back(base + d);
          out.push_back(-(base + d));
        }
  out.push_back(limit);
  out.push_back(-limit);
  return out;
}

TEST(TextureWrap, RepeatAndMirrorAreTheIntegerRemainderBelowTwoToThe24) {
  for (int n : {1, 2, 3, 5, 7, 64, 1000, 4095, 4096, 12345, 16384}) {
    for (int64_t i : coordinatesAround(n)) {
      ASSERT_EQ(wrapTexelCoord(int(i), n, kWrapRepeat), repeatReference(i, n)) << "repeat, i " << i << ", n " << n;
      ASSERT_EQ(wrapTexelCoord(int(i), n, kWrapMirror), mirrorReference(i, n)) << "mirror, i " << i << ", n " << n;
      ASSERT_EQ(wrapTexelCoord(int(i), n, kWrapClamp), int(i < 0 ? 0 : i >= n ? n - 1 : i)) << "clamp, i " << i;
    }
  }
}

TEST(TextureWrap, HugeCoordinatesStillNameATexel) {
  for (int n : {1, 3, 1000, 16384})
    for (int i : {int(1 << 24) + 1, 123456789, 2147483647, -2147483647, -(1 << 30)})
      for (uint32_t mode : {kWrapRepeat, kWrapMirror, kWrapClamp}) {
        const int m = wrapTexelCoord(i, n, mode);
        EXPECT_GE(m, 0) << i << " " << n << " " << mode;
        EXPECT_LT(m, n) << i << " " << n << " " << mode;
      }
}

// A 2x2 texture, top row first: red, green / blue, white (RGBA8, R in the low byte).
const uint32_t kQuad[4] = {0xFF0000FFu, 0xFF00FF00u, 0xFFFF0000u, 0xFFFFFFFFu};

glm::vec4 sampleQuad(uint32_t sampling, glm::vec2 uv) {
  static TextureGpu texture{};
  texture.offset = 0u;
  texture.width = 2u;
  texture.height = 2u;
  texture.sampling = sampling;
  texture_test_buffers::textures = &texture;
  texture_test_buffers::texels = kQuad;
  return sampleTexture(0, uv, false);
}

TEST(TextureFilter, NearestIsTheTexelThePointLiesInUnblended) {
  const uint32_t nearest = kWrapRepeat | (kWrapRepeat << 2u) | kTextureNearest;
  const glm::vec4 red(1, 0, 0, 1), green(0, 1, 0, 1), blue(0, 0, 1, 1), white(1, 1, 1, 1);
  // Across each texel, including near its edges (bilinear blends every one of these points).
  for (float a : {0.01f, 0.2f, 0.3f, 0.49f}) {
    for (float b : {0.01f, 0.26f, 0.49f}) {
      EXPECT_EQ(sampleQuad(nearest, {a, b}), red) << a << " " << b;
      EXPECT_EQ(sampleQuad(nearest, {a + 0.5f, b}), green) << a << " " << b;
      EXPECT_EQ(sampleQuad(nearest, {a, b + 0.5f}), blue) << a << " " << b;
      EXPECT_EQ(sampleQuad(nearest, {a + 0.5f, b + 0.5f}), white) << a << " " << b;
      // Repeat wrapping applies as for bilinear: one period to the left is the same texel.
      EXPECT_EQ(sampleQuad(nearest, {a - 1.0f, b + 0.5f}), blue) << a << " " << b;
    }
  }
}

TEST(TextureFilter, BilinearBlendsTheFourNearestTexelCentres) {
  const uint32_t linear = kWrapClamp | (kWrapClamp << 2u);
  // At a texel centre, that texel; midway between the four centres, their mean.
  EXPECT_EQ(sampleQuad(linear, {0.25f, 0.25f}), glm::vec4(1, 0, 0, 1));
  const glm::vec4 mid = sampleQuad(linear, {0.5f, 0.5f});
  EXPECT_NEAR(mid.x, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.y, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.z, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.w, 1.0f, 1e-6f);
}

}  // namespace

// The texture table stores each TextureGpu as the uvec4 of its bytes (shared/scene_buffers.h);
// textureFromWords must give back the record the host wrote, member for member.
TEST(TextureTable, WordsGiveBackTheHostsRecord) {
  TextureGpu host{};
  host.offset = 123456u;
  host.width = 640u;
  host.height = 7u;
  host.sampling = kWrapMirror | (kWrapClamp << 2u) | kTextureNearest;
  glm::uvec4 words;
  static_assert(sizeof(words) == sizeof(host), "one uvec4 per record");
  std::memcpy(&words, &host, sizeof(host));
  const TextureGpu back = textureFromWords(words);
  EXPECT_EQ(back.offset, host.offset);
  EXPECT_EQ(back.width, host.width);
  EXPECT_EQ(back.height, host.height);
  EXPECT_EQ(back.sampling, host.sampling);
}
