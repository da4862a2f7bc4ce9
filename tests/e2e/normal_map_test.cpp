// Normal maps (glTF normalTexture with its scale, tangents generated from the UVs), rendered by the
// real binary on both backends: a floor whose normal map tilts every normal the same way renders,
// for the same seed, the image of the same floor whose vertex normals are that tilted normal (the
// same paths: equal up to the map's 8 bits and the tangent's packing), and not the image of the
// flat floor. The scale enters: scale 0 is the flat floor's image. Normal-mapped shading normals
// never send light through the surface: a light below the floor leaves its top black.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "output/exr_io.h"
#include "support/analytic/gltf_writer.h"
#include "support/run_binary.h"
#include "support/image_difference.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using json = nlohmann::json;

// The map's one texel (linear RGB, 8 bits): a tangent-space normal tilted towards +u.
const int kTexel[3] = {170, 140, 230};

glm::dvec3 tangentSpaceNormal(double scale) {
  const glm::dvec3 c(kTexel[0] / 255.0 * 2.0 - 1.0, kTexel[1] / 255.0 * 2.0 - 1.0, kTexel[2] / 255.0 * 2.0 - 1.0);
  return glm::normalize(glm::dvec3(c.x * scale, c.y * scale, c.z));
}

std::string pngDataUri() {
  std::vector<uint8_t> png;
  const uint8_t pixel[3] = {uint8_t(kTexel[0]), uint8_t(kTexel[1]), uint8_t(kTexel[2])};
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
      },
      &png, 1, 1, 3, pixel, 3);
  return "data:image/png;base64," + analytic::base64Encode(png);
}

// A 2x2 floor in the XZ plane facing +Y (u along +x, v along +z: image up is -z), optionally with
// a normal map of `scale` or with every vertex normal set to `normal`, under a quad light at y =
// `lightY` facing `lightFacing` (+1: up, -1: down).
std::string floorScene(bool normalMap, double scale, const glm::dvec3* normal, double lightY, double lightFacing) {
  std::vector<float> data;
  auto push = [&](std::initializer_list<float> v) { data.insert(data.end(), v); };
  // floor positions (4), uvs (4), normals (4), light positions (4)
  push({-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1});
  push({0, 0, 1, 0, 1, 1, 0, 1});
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 n = normal ? *normal : glm::dvec3(0, 1, 0);
    push({float(n.x), float(n.y), float(n.z)});
  }
  const float y = float(lightY);
  push({-0.3f, y, -0.3f, 0.3f, y, -0.3f, 0.3f, y, 0.3f, -0.3f, y, 0.3f});
  std::vector<uint8_t> bytes(data.size() * 4);
  std::memcpy(bytes.data(), data.data(), bytes.size());
  const std::vector<uint16_t> up = {0, 2, 1, 0, 3, 2}, down = {0, 1, 2, 0, 2, 3};   // floor faces +y
  const std::vector<uint16_t>& lightIndices = lightFacing > 0 ? up : down;
  const size_t indexOffset = bytes.size();
  for (uint16_t i : up) bytes.insert(bytes.end(), {uint8_t(i), uint8_t(i >> 8)});
  for (uint16_t i : lightIndices) bytes.insert(bytes.end(), {uint8_t(i), uint8_t(i >> 8)});
  json views = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                            {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                            {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 48}},
                            {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 48}},
                            {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", 12}},
                            {{"buffer", 0}, {"byteOffset", indexOffset + 12}, {"byteLength", 12}}});
  json accessors = json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                                 {"min", {-1, 0, -1}}, {"max", {1, 0, 1}}},
                                {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                                {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                                {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                                 {"min", {-0.3, y, -0.3}}, {"max", {0.3, y, 0.3}}},
                                {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
                                {{"bufferView", 5}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}});
  json floorMaterial = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}}};
  if (normalMap) floorMaterial["normalTexture"] = {{"index", 0}, {"scale", scale}};
  json floorAttributes = {{"POSITION", 0}, {"TEXCOORD_0", 1}};
  if (normal) floorAttributes["NORMAL"] = 2;
  json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["scene"] = 0;
  doc["scenes"] = json::array({json{{"nodes", {0, 1, 2}}}});
  doc["nodes"] = json::array({json{{"mesh", 0}}, json{{"mesh", 1}},
                              json{{"camera", 0}, {"translation", {0, 1.6, 2.2}}, {"rotation", {-0.3106, 0, 0, 0.9505}}}});
  doc["cameras"] = json::array({json{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.01}}}}});
  doc["meshes"] = json::array(
      {json{{"primitives", json::array({json{{"attributes", floorAttributes}, {"indices", 4}, {"material", 0}}})}},
       json{{"primitives", json::array({json{{"attributes", {{"POSITION", 3}}}, {"indices", 5}, {"material", 1}}})}}});
  json light = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}}}, {"emissiveFactor", {1, 1, 1}}};
  light["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 10;
  doc["materials"] = json::array({floorMaterial, light});
  doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
  doc["images"] = json::array({json{{"uri", pngDataUri()}}});
  doc["textures"] = json::array({json{{"source", 0}}});
  doc["accessors"] = accessors;
  doc["bufferViews"] = views;
  doc["buffers"] = json::array(
      {json{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + analytic::base64Encode(bytes)}}});
  return doc.dump();
}

Image render(const fs::path& dir, const std::string& name, const std::string& gltf, const std::string& backend,
             const std::string& extra = "") {
  writeFile(dir / (name + ".gltf"), gltf);
  const RunResult r = runMixtrace("render " + (dir / (name + ".gltf")).string() +
                                  " --width 32 --height 24 --spp 16 --seed 9 --max-depth 2 --method pt-power --env none "
                                  "--no-png -q --backend " + backend + " " + extra + " --out " + (dir / (name + ".exr")).string());
  EXPECT_EQ(r.exitCode, 0) << name << ": " << r.stderrText;
  return readExr((dir / (name + ".exr")).string());
}


class NormalMap : public ::testing::TestWithParam<const char*> {};

TEST_P(NormalMap, TiltsTheShadingNormalAsTheSameVertexNormalsDo) {
  const fs::path dir = scratchDir("normal-map");
  // The map's normal in the floor's tangent frame: T = +x, B = w cross(+y, +x) = -z (up the
  // image, w = +1), N = +y.
  const glm::dvec3 ts = tangentSpaceNormal(1.0);
  const glm::dvec3 tilted = glm::normalize(glm::dvec3(ts.x, ts.z, -ts.y));
  const Image mapped = render(dir, "mapped", floorScene(true, 1.0, nullptr, 1.2, -1), GetParam());
  const Image normals = render(dir, "normals", floorScene(false, 1.0, &tilted, 1.2, -1), GetParam());
  const Image flat = render(dir, "flat", floorScene(false, 1.0, nullptr, 1.2, -1), GetParam());
  const Image scaledAway = render(dir, "scale0", floorScene(true, 0.0, nullptr, 1.2, -1), GetParam());
  EXPECT_EQ(differingChannels(mapped, normals, 2e-3f), 0u);
  EXPECT_GT(differingChannels(mapped, flat, 2e-3f), mapped.rgb.size() / 4) << "the map changes nothing visible";
  EXPECT_EQ(differingChannels(scaledAway, flat, 2e-3f), 0u);
  // The fully general pipelines (every feature compiled in) render the same image for the same seed.
  const Image general = render(dir, "mapped-general", floorScene(true, 1.0, nullptr, 1.2, -1), GetParam(), "--general-pipelines");
  EXPECT_EQ(differingChannels(general, mapped, 1e-4f), 0u);
}

// A light under the floor facing up at it: it lights the floor's underside (the BSDF is two-sided)
// but nothing of the top the camera sees, however its normals lean.
TEST_P(NormalMap, NeverSendsLightThroughTheSurface) {
  const fs::path dir = scratchDir("normal-map-leak");
  const Image img = render(dir, "below", floorScene(true, 1.0, nullptr, -0.5, +1), GetParam());
  for (float v : img.rgb) ASSERT_EQ(v, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, NormalMap, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
