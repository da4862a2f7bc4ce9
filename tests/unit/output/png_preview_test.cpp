// PNG preview: written file decodes to the exact sRGB curve, non-finite values become black.
#include "output/png_preview.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "support/scratch_files.h"
#include "util/error.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

namespace mixtrace {
namespace {

class PngPreview : public mixtrace::testing::ScratchFiles {};

struct Decoded {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

Decoded decode(const std::string& path) {
  Decoded result;
  int channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &result.width, &result.height, &channels, 3);
  EXPECT_NE(pixels, nullptr) << "cannot decode " << path;
  EXPECT_EQ(channels, 3);
  if (pixels) {
    result.rgb.assign(pixels, pixels + static_cast<size_t>(result.width) * result.height * 3);
    stbi_image_free(pixels);
  }
  return result;
}

// Expected bytes come from the sRGB definition evaluated in double precision elsewhere
// (round(255 * oetf(v))); a plain gamma-2.2 curve would give 15 for 0.002, not 7.
struct CurvePoint {
  float linear;
  int expected;
};
const CurvePoint kCurve[] = {
    {0.0f, 0},    {1.0f, 255},   {0.5f, 188},   {0.18f, 118}, {0.25f, 137},     {0.001f, 3},
    {0.002f, 7},  {0.003f, 10},  {0.0031308f, 10}, {0.004f, 13}, {-0.5f, 0}, {7.0f, 255},
};

TEST_F(PngPreview, WritesTheExactSrgbCurve) {
  const int count = static_cast<int>(sizeof(kCurve) / sizeof(kCurve[0]));
  // One row; each pixel carries a curve point in R, and its neighbours' points in G and B so
  // that channel order mistakes show.
  Image image(count, 2);
  for (int x = 0; x < count; ++x)
    for (int c = 0; c < 3; ++c) {
      image.pixel(x, 0)[c] = kCurve[(x + c) % count].linear;
      image.pixel(x, 1)[c] = kCurve[(x + c + 1) % count].linear;
    }
  const std::string path = tempPath("curve.png");
  writePngPreview(path, image);
  const Decoded png = decode(path);
  ASSERT_EQ(png.width, count);
  ASSERT_EQ(png.height, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < count; ++x)
      for (int c = 0; c < 3; ++c) {
        const CurvePoint& point = kCurve[(x + c + y) % count];
        EXPECT_EQ(png.rgb[3 * (y * count + x) + c], point.expected) << "linear " << point.linear;
      }
}

TEST_F(PngPreview, LinearSegmentAndPowerSegmentMeetAtTheBoundary) {
  // Just below and above 0.0031308 the two pieces of the curve agree (continuity), and the
  // linear piece is really linear: 12.92 * v.
  EXPECT_EQ(linearToSrgb8(0.0031307f), linearToSrgb8(0.0031309f));
  EXPECT_EQ(linearToSrgb8(0.0031308f), 10);
  EXPECT_EQ(linearToSrgb8(0.0001f), 0);  // 12.92e-4 * 255 = 0.33
  EXPECT_EQ(linearToSrgb8(0.0002f), 1);  // 0.66
  EXPECT_EQ(linearToSrgb8(0.0015f), 5);  // 4.94
}

TEST_F(PngPreview, ExposureScalesBeforeTheCurve) {
  EXPECT_EQ(linearToSrgb8(0.25f, 2.0f), 188);
  EXPECT_EQ(linearToSrgb8(1.0f, 0.5f), 188);
  Image image(1, 1);
  image.rgb = {0.125f, 0.25f, 0.5f};
  const std::string path = tempPath("exposure.png");
  writePngPreview(path, image, 4.0f);
  const Decoded png = decode(path);
  ASSERT_EQ(png.rgb.size(), 3u);
  EXPECT_EQ(png.rgb[0], 188);
  EXPECT_EQ(png.rgb[1], 255);
  EXPECT_EQ(png.rgb[2], 255);
}

TEST_F(PngPreview, NonFiniteValuesBecomeBlack) {
  Image image(2, 1);
  image.rgb = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
               -std::numeric_limits<float>::infinity(), 1.0f, std::numeric_limits<float>::quiet_NaN(), 0.5f};
  const std::string path = tempPath("nan.png");
  writePngPreview(path, image);
  const Decoded png = decode(path);
  ASSERT_EQ(png.rgb.size(), 6u);
  EXPECT_EQ(png.rgb[0], 0);
  EXPECT_EQ(png.rgb[1], 0);
  EXPECT_EQ(png.rgb[2], 0);
  EXPECT_EQ(png.rgb[3], 255);
  EXPECT_EQ(png.rgb[4], 0);
  EXPECT_EQ(png.rgb[5], 188);
}

TEST_F(PngPreview, ErrorOnUnwritablePath) {
  Image image(1, 1);
  const std::string path = tempPath("no_such_dir") + "/sub/x.png";
  try {
    writePngPreview(path, image);
    ADD_FAILURE() << "no Error thrown";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST_F(PngPreview, DefaultPreviewPath) {
  EXPECT_EQ(defaultPreviewPath("out.exr"), "out.png");
  EXPECT_EQ(defaultPreviewPath("renders/cornell.exr"), "renders/cornell.png");
  EXPECT_EQ(defaultPreviewPath("dir.v2/image"), "dir.v2/image.png");
  EXPECT_EQ(defaultPreviewPath("/tmp/a.b.exr"), "/tmp/a.b.png");
}

}  // namespace
}  // namespace mixtrace
