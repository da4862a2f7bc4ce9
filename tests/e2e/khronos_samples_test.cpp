// Khronos glTF sample models (tests/data/khronos/, each with its licence), rendered by the real
// binary: each test checks what its model exists to show.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "output/exr_io.h"
#include "support/pfm_writer.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"
#include "support/image_difference.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

fs::path sample(const std::string& name) {
  return fs::path(MIXTRACE_SOURCE_DIR) / "tests/data/khronos" / name / (name + ".gltf");
}

float luminanceAt(const Image& img, int x, int y) {
  const size_t p = 3 * (size_t(y) * img.width + x);
  return 0.2126f * img.rgb[p] + 0.7152f * img.rgb[p + 1] + 0.0722f * img.rgb[p + 2];
}

// SimpleSparseAccessor: a strip 6 wide and 1 high whose sparse accessor lifts three top vertices to
// y = 2, 3 and 4. Seen face on (camera at (3, 2, 10) towards -Z, 40 degrees: a 7.28-unit square at
// z = 0 on 48x48 pixels), lit from behind the camera (an environment bright only towards +Z, so
// the background is black): the spike at x = 5 reaches y = 3.5, where without the substitution
// there is nothing. The file has no lights and no camera.
class SimpleSparseAccessor : public ::testing::TestWithParam<const char*> {};

TEST_P(SimpleSparseAccessor, TheSubstitutedVerticesShapeTheStrip) {
  const fs::path dir = scratchDir("khronos-sparse");
  std::vector<glm::vec3> map(8 * 4, glm::vec3(0.0f));
  for (int y = 0; y < 4; ++y)
    for (int x = 2; x < 6; ++x) map[size_t(y) * 8 + x] = glm::vec3(1.0f);   // u in [1/4, 3/4): +Z
  writePfm(dir / "behind.pfm", 8, 4, map);
  const fs::path out = dir / "sparse.exr";
  const RunResult r = runMixtrace("render " + sample("SimpleSparseAccessor").string() + " --env " +
                                  (dir / "behind.pfm").string() +
                                  " --look-from 3,2,10 --look-at 3,2,0 --fov 40 --width 48 --height 48 --spp 16 "
                                  "--max-depth 2 --no-png -q --backend " + GetParam() + " --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const Image img = readExr(out.string());
  auto pixelOf = [](double x, double y) {
    const double half = 10.0 * std::tan(20.0 * 3.14159265358979323846 / 180.0);
    return std::pair<int, int>{int((x - 3.0 + half) / (2.0 * half) * 48.0), int((2.0 + half - y) / (2.0 * half) * 48.0)};
  };
  const auto [spikeX, spikeY] = pixelOf(5.0, 3.4);   // inside the tallest spike only with the substitution
  const auto [gapX, gapY] = pixelOf(2.0, 3.4);       // between spikes: background
  const auto [baseX, baseY] = pixelOf(2.5, 0.5);     // the strip's body
  EXPECT_GT(luminanceAt(img, spikeX, spikeY), 0.05f) << "the spike at x = 5 is missing";
  EXPECT_GT(luminanceAt(img, baseX, baseY), 0.05f);
  EXPECT_EQ(luminanceAt(img, gapX, gapY), 0.0f);
  const auto [aboveX, aboveY] = pixelOf(5.0, 4.6);   // above the spike's top
  EXPECT_EQ(luminanceAt(img, aboveX, aboveY), 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimpleSparseAccessor, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

// TextureCoordinateTest: four unit quads facing -Z (x, y in [0.2, 1.2] or [-1.2, -0.2], z = 0) in
// front of a grey plane, each reading one corner of the same 512x512 texture (U and V 0-0.4 or
// 0.6-1, V = 0 the image's top row) through its own base colour factor. The texture is white but
// for a chequered L at each corner and the labels "Top Left", "Top Right" (one line, texture rows
// 53-71) and "Bottom / Left", "Bottom / Right" (two lines, rows 426-438 and 447-464). Read the
// right way, each quad carries its own label, upright, at its outer corner; a renderer that flips
// V shows the opposite corner's label upside down instead (on the top-left quad, "Bottom Left":
// two lines at rows 52-86, so text below row 75 and a paler first line; on the bottom quads,
// nothing on rows 426-438). Each quad is seen face on from z = -2 (the camera looks towards +Z,
// so +X is on the image's left), 30 degrees: 1.07 units, 3.4 texture pixels a pixel, on 64x64.
// Boxes are given in texture pixels and measured as the mean R+G+B of the pixels whose centres
// fall in them, over the same sum on a plain white stretch of the quad (the box's coverage by
// ink, inverted): a box holding a label line measures 0.55-0.8 (its ink covers 20-40%), a blank
// one 0.98-1.04 at 16 spp, and a V-flipped texture moves the label rows to 0.87-1.04 and the
// blank ones to 0.73-0.82. The plain stretch's colour is the quad's factor: the material is the
// default metallic 1, roughness 1, so its colour is the base colour (texture white x factor)
// times one grey albedo. The file has no lights: a uniform white environment lights it.
class TextureCoordinateTest : public ::testing::TestWithParam<const char*> {};

TEST_P(TextureCoordinateTest, EachQuadShowsItsOwnLabelUprightInItsOwnColour) {
  struct Box {
    const char* what;
    double col0, col1, row0, row1;   // texture pixels, inclusive
    bool inked;                      // holds a label line (else blank)
  };
  struct Quad {
    const char* name;
    double x0, y0;            // the quad spans [x0, x0 + 1] x [y0, y0 + 1]
    double u0, v0;            // its UVs span [u0, u0 + 0.4] x [v0, v0 + 0.4], U growing towards -X, V towards -Y
    glm::vec3 factor;         // its base colour factor
    Box plain;                // white texture: the reference
    std::vector<Box> boxes;
  };
  const std::vector<Quad> quads = {
      {"TopLeft", 0.2, 0.2, 0.0, 0.0, {1.0f, 1.0f, 0.0f}, {"plain", 50, 150, 100, 160, false},
       {{"the label \"Top Left\"", 44, 115, 54, 71, true}, {"below the label", 44, 115, 76, 90, false}}},
      {"TopRight", -1.2, 0.2, 0.6, 0.0, {1.0f, 0.1f, 0.0f}, {"plain", 360, 460, 100, 160, false},
       {{"the label \"Top Right\"", 381, 465, 53, 70, true}, {"below the label", 381, 465, 76, 90, false}}},
      {"BottomLeft", 0.2, -1.2, 0.0, 0.6, {0.0f, 0.2f, 1.0f}, {"plain", 50, 150, 350, 395, false},
       {{"the label's line \"Bottom\"", 44, 105, 426, 438, true},
        {"the label's line \"Left\"", 44, 105, 447, 460, true},
        {"above the label", 44, 115, 400, 420, false}}},
      {"BottomRight", -1.2, -1.2, 0.6, 0.6, {0.0f, 1.0f, 0.0f}, {"plain", 360, 460, 350, 395, false},
       {{"the label's line \"Bottom\"", 405, 468, 426, 438, true},
        {"the label's line \"Right\"", 405, 468, 447, 464, true},
        {"above the label", 381, 468, 400, 420, false}}},
  };
  const fs::path dir = scratchDir("khronos-texcoord");
  const int size = 64;
  const double half = 2.0 * std::tan(15.0 * 3.14159265358979323846 / 180.0);   // half the view at z = 0
  for (const Quad& q : quads) {
    SCOPED_TRACE(q.name);
    const double cx = q.x0 + 0.5, cy = q.y0 + 0.5;
    std::ostringstream camera;
    camera << " --look-from " << cx << "," << cy << ",-2 --look-at " << cx << "," << cy << ",0";
    const fs::path out = dir / (std::string(q.name) + ".exr");
    const RunResult r = runMixtrace("render " + sample("TextureCoordinateTest").string() + camera.str() +
                                    " --fov 30 --width 64 --height 64 --spp 16 --max-depth 2 --no-png -q --backend " +
                                    GetParam() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const Image img = readExr(out.string());
    // The mean colour of the pixels whose centres map inside a box of texture pixels.
    auto meanIn = [&](const Box& b) {
      glm::dvec3 sum(0.0);
      int n = 0;
      for (int y = 0; y < size; ++y) {
        const double wy = cy + half - (y + 0.5) * 2.0 * half / size;
        const double row = q.v0 * 512.0 + (q.y0 + 1.0 - wy) * 204.8;
        if (row < b.row0 || row > b.row1) continue;
        for (int x = 0; x < size; ++x) {
          const double wx = cx + half - (x + 0.5) * 2.0 * half / size;   // image right is -X
          const double col = q.u0 * 512.0 + (q.x0 + 1.0 - wx) * 204.8;
          if (col < b.col0 || col > b.col1) continue;
          const size_t p = 3 * (size_t(y) * size + x);
          sum += glm::dvec3(img.rgb[p], img.rgb[p + 1], img.rgb[p + 2]);
          ++n;
        }
      }
      EXPECT_GT(n, 40) << b.what;
      return n > 0 ? sum / double(n) : sum;
    };
    const glm::dvec3 plain = meanIn(q.plain);
    const double plainSum = plain.x + plain.y + plain.z;
    ASSERT_GT(plainSum, 0.05);
    const glm::dvec3 factor(q.factor);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(plain[c] / plainSum, factor[c] / (factor.x + factor.y + factor.z), 0.03)
          << "channel " << c << " of the quad's colour";
    for (const Box& b : q.boxes) {
      const glm::dvec3 m = meanIn(b);
      const double ratio = (m.x + m.y + m.z) / plainSum;
      if (b.inked) EXPECT_LT(ratio, 0.85) << b.what << " is not where the label must land (V flipped?)";
      else EXPECT_GT(ratio, 0.9) << b.what << " should be blank (V flipped?)";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, TextureCoordinateTest, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

// BoxVertexColors: a unit cube (+-0.5) whose corners carry different COLOR_0 values multiplying
// a grey base colour (0.8; metallic 0.1, roughness 0.99). Its +Z face, seen face on from z = 3
// (30 degrees: 1.34 units at z = 0.5 on 48x48 pixels), is split along the diagonal from (-0.5,
// -0.5) to (0.5, 0.5) into the triangles (top right, bottom left, bottom right) and (top left,
// bottom left, top right); the corners' colours (linear, as the file stores them): top right
// red (1.0, 0.001, 0.025), top left yellow-green (0.511, 1, 0), bottom left grey (0.804 each),
// bottom right blue (0.003, 0.131, 0.999). At a point 80% of the way to a corner the colour is
// the barycentric blend of the triangle's three corners (0.8 of that corner, 0.1 of each other),
// and a diffuse-dominated surface under a uniform white environment shows it in proportion: the
// chromaticity of a 3x3 block there matches the blend's within 0.04 (the small specular part,
// the same for all channels, pulls it towards grey by up to 0.025). A renderer that ignores
// COLOR_0 shows grey (1/3 each) everywhere; one that read the alpha (0 at the red and blue
// corners) as coverage of this OPAQUE material would show the white environment through them.
class BoxVertexColors : public ::testing::TestWithParam<const char*> {};

TEST_P(BoxVertexColors, CornerColoursBlendAcrossTheFace) {
  const fs::path dir = scratchDir("khronos-boxvertexcolors");
  const fs::path out = dir / "box.exr";
  const int size = 48;
  const RunResult r = runMixtrace("render " + sample("BoxVertexColors").string() +
                                  " --look-from 0,0,3 --look-at 0,0,0 --fov 30 --width 48 --height 48 --spp 16 "
                                  "--max-depth 2 --no-png -q --backend " + GetParam() + " --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const Image img = readExr(out.string());
  const glm::dvec3 topRight(0.9997, 0.0012, 0.0247), topLeft(0.5109, 1.0, 0.0), bottomLeft(0.8039),
      bottomRight(0.0025, 0.1314, 0.9994);
  // The vertex colour the face interpolates at (x, y) on z = 0.5.
  auto blend = [&](double x, double y) {
    if (x > y) {   // triangle (top right, bottom left, bottom right)
      const double a = y + 0.5, c = x - y;
      return a * topRight + (1.0 - a - c) * bottomLeft + c * bottomRight;
    }
    const double t = y - x, rr = x + 0.5;   // triangle (top left, bottom left, top right)
    return t * topLeft + (1.0 - t - rr) * bottomLeft + rr * topRight;
  };
  const double half = 2.5 * std::tan(15.0 * 3.14159265358979323846 / 180.0);
  const struct {
    const char* near;
    double x, y;
  } points[] = {{"top right (red)", 0.4, 0.3},
                {"top left (yellow-green)", -0.3, 0.4},
                {"bottom left (grey)", -0.4, -0.3},
                {"bottom right (blue)", 0.3, -0.4}};
  for (const auto& p : points) {
    const int px = int((p.x + half) / (2.0 * half) * size), py = int((half - p.y) / (2.0 * half) * size);
    glm::dvec3 sum(0.0);
    for (int y = py - 1; y <= py + 1; ++y)
      for (int x = px - 1; x <= px + 1; ++x) {
        const size_t i = 3 * (size_t(y) * size + x);
        sum += glm::dvec3(img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]);
      }
    const glm::dvec3 expected = blend(p.x, p.y);
    const double gotTotal = sum.x + sum.y + sum.z, expectedTotal = expected.x + expected.y + expected.z;
    ASSERT_GT(gotTotal, 0.0) << p.near;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(sum[c] / gotTotal, expected[c] / expectedTotal, 0.04) << "near the " << p.near << " corner, channel " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, BoxVertexColors, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

// MultiUVTest: a cube (+-1) whose one material reads its base colour texture through TEXCOORD_0
// and its emissive texture (factor 1) through TEXCOORD_1, both 1024x1024. TEXCOORD_0 unfolds the
// faces as a cross over the base colour image, each face on its own pastel square (the +Z face on
// the yellow one, sRGB (255, 247, 153), at U 0.25-0.5, V 0-0.25); TEXCOORD_1 puts every face on
// the emissive image's top-left quarter (U, V 0-0.25): a green and white glTF logo on black. The
// emissive image holds, right of it (U 0.25-0.5), the words "Multiple UVs / not supported / in this
// viewer" in white: what a renderer that reads the emission through TEXCOORD_0 shows instead of
// the logo; and the base colour image is white at U, V 0-0.25: what one that reads the base colour
// through TEXCOORD_1 shows instead of yellow. On the +Z face both sets are upright and a point
// (x, y, 1) reads texture pixel ((x + 1) * 128, (1 - y) * 128) of its 256x256 quarter (offset by
// 256 columns through TEXCOORD_0). Boxes of quarter pixels: the logo's top rows (96-112, columns
// 48-208) are black in the words' quarter; the words' first line (rows 64-80) lies above the logo;
// rows 200-248 are black in both. Seen face on from z = 5 (the camera looks towards -Z with +Y up,
// so +X is on the image's right), 30 degrees: 2.14 units at z = 1 on 64x64 pixels, 3.8 texture
// pixels a pixel. Without an environment only the emission shows: the logo's box measures a mean
// linear (R, G, B) of (0.105, 0.241, 0.022), green (nothing there through TEXCOORD_0), and the
// words' box a sum of 0.010, the logo's edge (0.63, white, through TEXCOORD_0). Under a uniform
// white environment (needed: the emissive texture makes the file's default environment black) the
// black-emission box shows the base colour: the material is the default metallic 1, roughness 1,
// so its chromaticity is the yellow's, linear (1, 0.930, 0.318) / 2.248 = (0.445, 0.414, 0.142),
// within 0.03 (measured (0.445, 0.414, 0.142); white, through TEXCOORD_1, is a third each).
class MultiUVTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MultiUVTest, EmissionReadsTexcoord1AndBaseColourTexcoord0) {
  struct Box {
    double col0, col1, row0, row1;   // pixels of the 256x256 texture quarter, inclusive
  };
  const Box logoOnly{48, 208, 96, 112}, wordsOnly{48, 208, 64, 80}, neither{24, 232, 200, 248};
  const fs::path dir = scratchDir("khronos-multiuv");
  const int size = 64;
  const double half = 4.0 * std::tan(15.0 * 3.14159265358979323846 / 180.0);   // half the view at z = 1
  const std::string common = sample("MultiUVTest").string() +
                             " --look-from 0,0,5 --look-at 0,0,0 --up 0,1,0 --fov 30 --width 64 --height 64 --spp 16 "
                             "--max-depth 2 --backend " + std::string(GetParam());
  // The mean colour of the pixels whose centres map inside a box.
  auto meanIn = [&](const Image& img, const Box& b) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = 0; y < size; ++y) {
      const double row = (1.0 - (half - (y + 0.5) * 2.0 * half / size)) * 128.0;
      if (row < b.row0 || row > b.row1) continue;
      for (int x = 0; x < size; ++x) {
        const double col = (-half + (x + 0.5) * 2.0 * half / size + 1.0) * 128.0;
        if (col < b.col0 || col > b.col1) continue;
        const size_t p = 3 * (size_t(y) * size + x);
        sum += glm::dvec3(img.rgb[p], img.rgb[p + 1], img.rgb[p + 2]);
        ++n;
      }
    }
    EXPECT_GE(n, 40);
    return n > 0 ? sum / double(n) : sum;
  };

  // The emission alone.
  const RenderWithStats emission = renderWithStats(common + " --env none", dir / "emission.exr", 300);
  ASSERT_EQ(emission.exitCode, 0) << emission.stderrText;
  const glm::dvec3 logo = meanIn(emission.mean, logoOnly), words = meanIn(emission.mean, wordsOnly);
  EXPECT_GT(logo.y, 0.1) << "no logo where TEXCOORD_1 puts it (emission read through TEXCOORD_0?)";
  EXPECT_GT(logo.y, 1.5 * logo.x) << "the logo is green";
  EXPECT_GT(logo.y, 3.0 * logo.z) << "the logo is green";
  EXPECT_LT(words.x + words.y + words.z, 0.05) << "the words TEXCOORD_0 would show are lit (emission read through TEXCOORD_0?)";
  EXPECT_NE(emission.stats["features"].get<std::string>().find("second-uvs=1"), std::string::npos)
      << emission.stats["features"];

  // Lit by a uniform white environment: the base colour.
  const RenderWithStats lit = renderWithStats(common + " --env-color 1,1,1", dir / "lit.exr", 300);
  ASSERT_EQ(lit.exitCode, 0) << lit.stderrText;
  const glm::dvec3 base = meanIn(lit.mean, neither);
  const double total = base.x + base.y + base.z;
  ASSERT_GT(total, 0.05);
  const glm::dvec3 yellow(1.0, 0.930, 0.318);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(base[c] / total, yellow[c] / (yellow.x + yellow.y + yellow.z), 0.03)
        << "channel " << c << " of the base colour (read through TEXCOORD_1?)";
  EXPECT_NE(lit.stats["features"].get<std::string>().find("second-uvs=1"), std::string::npos) << lit.stats["features"];

  // The fully general pipelines render the same image for the same seed.
  const RenderWithStats general = renderWithStats(common + " --env-color 1,1,1 --general-pipelines", dir / "general.exr", 300);
  ASSERT_EQ(general.exitCode, 0) << general.stderrText;
  EXPECT_EQ(differingChannels(general.mean, lit.mean, 1e-4f, 0.0f), 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, MultiUVTest, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
