// glTF COLOR_0 multiplies the base colour (rendered by the real binary, both backends):
//   - a plane whose vertex colour is c everywhere renders, for the same seed, the image of the same
//     plane with base colour b x c and no COLOR_0 (the same paths: equal to float rounding and the
//     colour's 16-bit storage), and not the image of the plane without its colour;
//   - colours are interpolated across the triangle (a red-to-green ramp shows both ends);
//   - the specialised pipelines (vertex-colors=1 only where a triangle has a colour) render what the
//     fully general ones do, and the stats name the feature.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "output/exr_io.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

const glm::vec3 kBase(0.8f, 0.7f, 0.9f);
const glm::vec4 kVertexColour(0.25f, 0.5f, 1.0f, 1.0f);

// A floor (with `floorColors` as COLOR_0) under a quad light, seen from above at an angle.
fs::path writeFloorScene(const fs::path& dir, const std::string& name, glm::vec3 base,
                         const std::vector<glm::vec4>& floorColors) {
  GltfWriter w;
  w.addMesh(rectangle({-1.0, 0.0, 1.0}, {2.0, 0.0, 0.0}, {0.0, 0.0, -2.0}, {0.0, 1.0, 0.0}),
            w.addMaterial(MaterialSpec{base, 0.0f, 0.7f, glm::vec3(0.0f), false}), floorColors);
  w.addMesh(rectangle({-0.4, 1.5, -0.4}, {0.8, 0.0, 0.0}, {0.0, 0.0, 0.8}, {0.0, -1.0, 0.0}),
            w.addMaterial(MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(8.0f), false}));
  CameraSpec camera;
  camera.position = {0.0, 2.2, 2.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.yfov = 0.9;
  w.setCamera(camera);
  const fs::path path = dir / (name + ".gltf");
  writeFile(path, w.json());
  return path;
}

Image render(const fs::path& scene, const std::string& backend, const std::string& extra, nlohmann::json* stats = nullptr) {
  const fs::path out = fs::path(scene).replace_extension(".exr");
  const RenderWithStats r = renderWithStats(scene.string() + " --width 32 --height 24 --spp 16 --seed 5 --max-depth 3 --backend " +
                                                backend + " " + extra,
                                            out, 600);
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  if (stats) *stats = r.stats;
  return r.mean;
}

// Pixels whose values differ beyond float rounding and 16-bit colour storage.
size_t differingPixels(const Image& a, const Image& b) {
  EXPECT_EQ(a.rgb.size(), b.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < std::min(a.rgb.size(), b.rgb.size()); ++i)
    if (std::abs(a.rgb[i] - b.rgb[i]) > 2e-4f * std::max(1.0f, std::abs(b.rgb[i]))) ++differing;
  return differing;
}

class VertexColor : public ::testing::TestWithParam<const char*> {};

TEST_P(VertexColor, MultipliesTheBaseColour) {
  const fs::path dir = scratchDir("vertex-color");
  const std::vector<glm::vec4> constant(6, kVertexColour);
  nlohmann::json stats, plainStats;
  const Image coloured = render(writeFloorScene(dir, "coloured", kBase, constant), GetParam(), "", &stats);
  const Image baked = render(writeFloorScene(dir, "baked", kBase * glm::vec3(kVertexColour), {}), GetParam(), "", &plainStats);
  const Image uncoloured = render(writeFloorScene(dir, "uncoloured", kBase, {}), GetParam(), "");
  const Image general = render(dir / "coloured.gltf", GetParam(), "--general-pipelines");
  EXPECT_EQ(differingPixels(coloured, baked), 0u);
  EXPECT_GT(differingPixels(coloured, uncoloured), coloured.rgb.size() / 8);  // the test sees a missing colour
  EXPECT_EQ(differingPixels(coloured, general), 0u);
  EXPECT_NE(stats["features"].get<std::string>().find("vertex-colors=1"), std::string::npos) << stats["features"];
  EXPECT_NE(plainStats["features"].get<std::string>().find("vertex-colors=0"), std::string::npos) << plainStats["features"];
}

// Red at x = -1, green at x = +1 (the rectangle's corners: (-1,0,1) (1,0,1) (1,0,-1) / (-1,0,1)
// (1,0,-1) (-1,0,-1)): the left of the image is red, the right green.
TEST_P(VertexColor, IsInterpolatedAcrossTheTriangle) {
  const fs::path dir = scratchDir("vertex-ramp");
  const std::vector<Tri> floor = rectangle({-1.0, 0.0, 1.0}, {2.0, 0.0, 0.0}, {0.0, 0.0, -2.0}, {0.0, 1.0, 0.0});
  std::vector<glm::vec4> ramp;
  for (const Tri& t : floor)
    for (const glm::vec3& p : t.p) ramp.push_back(p.x < 0.0f ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 1, 0, 1));
  const Image img = render(writeFloorScene(dir, "ramp", glm::vec3(1.0f), ramp), GetParam(), "");
  double left[3] = {0, 0, 0}, right[3] = {0, 0, 0}, middle[3] = {0, 0, 0};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      double* side = x < img.width / 4 ? left : x >= 3 * img.width / 4 ? right : (x >= 7 * img.width / 16 && x < 9 * img.width / 16) ? middle : nullptr;
      if (!side) continue;
      for (int c = 0; c < 3; ++c) side[c] += img.rgb[3 * (size_t(y) * img.width + x) + c];
    }
  EXPECT_GT(left[0], 5.0 * left[1]) << "left: red " << left[0] << " green " << left[1];
  EXPECT_GT(right[1], 5.0 * right[0]) << "right: red " << right[0] << " green " << right[1];
  // Half way, both.
  EXPECT_GT(middle[0], 0.3 * middle[1]);
  EXPECT_GT(middle[1], 0.3 * middle[0]);
  // Blue only from the dielectric's untinted specular lobe: the colour multiplies the diffuse part.
  EXPECT_LT(left[2] + right[2], 0.2 * (left[0] + right[1]));
}

INSTANTIATE_TEST_SUITE_P(Backends, VertexColor, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
