// Tests of loadGltf. Every case writes a small glTF (JSON with a base64 buffer, or .glb) into a
// temporary directory at run time, so no binary fixtures live in the repository.
#include "gltf/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "shared/constants.h"
#include "util/error.h"

// stb_image_write is compiled into this test only, with internal linkage, so it cannot clash with
// the copy of stb that libtinygltf links.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;
using mixtrace::Scene;

constexpr int kUByte = 5121;
constexpr int kUShort = 5123;
constexpr int kUInt = 5125;
constexpr int kFloat = 5126;

// --- Building glTF files -----------------------------------------------------------------------

std::string base64(const std::vector<uint8_t>& data) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    const uint32_t b0 = data[i];
    const uint32_t b1 = i + 1 < data.size() ? data[i + 1] : 0;
    const uint32_t b2 = i + 2 < data.size() ? data[i + 2] : 0;
    const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < data.size() ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void appendU32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

struct GltfBuilder {
  json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  int view(const void* data, size_t size, int stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    const auto* bytes = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), bytes, bytes + size);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (stride) v["byteStride"] = stride;
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size()) - 1;
  }
  int accessor(int viewIndex, int componentType, size_t count, const char* type, size_t byteOffset = 0,
               bool normalized = false) {
    json a = {{"bufferView", viewIndex}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (byteOffset) a["byteOffset"] = byteOffset;
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size()) - 1;
  }
  int vec3s(const std::vector<glm::vec3>& v) {
    return accessor(view(v.data(), v.size() * sizeof(glm::vec3)), kFloat, v.size(), "VEC3");
  }
  int vec2s(const std::vector<glm::vec2>& v) {
    return accessor(view(v.data(), v.size() * sizeof(glm::vec2)), kFloat, v.size(), "VEC2");
  }
  template <class T>
  int scalars(const std::vector<T>& v, int componentType) {
    return accessor(view(v.data(), v.size() * sizeof(T)), componentType, v.size(), "SCALAR");
  }
  int mesh(const json& primitives) {
    doc["meshes"].push_back({{"primitives", primitives}});
    return int(doc["meshes"].size()) - 1;
  }
  int node(const json& n) {
    doc["nodes"].push_back(n);
    return int(doc["nodes"].size()) - 1;
  }
  void scene(const std::vector<int>& roots) {
    doc["scenes"] = json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }
  // A mesh with one triangle (0,0,0) (1,0,0) (0,1,0): counter-clockwise seen from +Z.
  int triangleMesh(const json& extra = json::object()) {
    json primitive = {{"attributes", {{"POSITION", vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}}};
    primitive.update(extra);
    return mesh(json::array({primitive}));
  }

  std::string writeGltf(const fs::path& dir, const std::string& name = "scene.gltf") {
    json d = doc;
    if (!bin.empty()) {
      d["buffers"] = json::array(
          {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    }
    const fs::path path = dir / name;
    std::ofstream(path) << d.dump(1);
    return path.string();
  }
  std::vector<uint8_t> glbBytes() const {
    json d = doc;
    std::vector<uint8_t> payload = bin;
    while (payload.size() % 4) payload.push_back(0);
    if (!payload.empty()) d["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = d.dump();
    while (text.size() % 4) text += ' ';
    std::vector<uint8_t> out = {'g', 'l', 'T', 'F'};
    appendU32(out, 2);
    appendU32(out, uint32_t(12 + 8 + text.size() + (payload.empty() ? 0 : 8 + payload.size())));
    appendU32(out, uint32_t(text.size()));
    appendU32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    if (!payload.empty()) {
      appendU32(out, uint32_t(payload.size()));
      appendU32(out, 0x004E4942u);  // "BIN\0"
      out.insert(out.end(), payload.begin(), payload.end());
    }
    return out;
  }
  std::string writeGlb(const fs::path& dir, const std::string& name = "scene.glb") const {
    const fs::path path = dir / name;
    writeBytes(path, glbBytes());
    return path.string();
  }
};

class GltfLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static int counter = 0;
    dir_ = fs::temp_directory_path() /
           ("mixtrace_gltf_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Loads `path` and returns what the loader printed to stderr (its warnings).
  Scene loadCapturing(const std::string& path, std::string& warnings) {
    ::testing::internal::CaptureStderr();
    try {
      Scene scene = mixtrace::loadGltf(path);
      warnings = ::testing::internal::GetCapturedStderr();
      return scene;
    } catch (...) {
      warnings = ::testing::internal::GetCapturedStderr();
      throw;
    }
  }

  // One triangle for each material of b's document (triangle i has material i), loaded with its
  // warnings.
  Scene loadTrianglePerMaterial(GltfBuilder& b, std::string& warnings) {
    json primitives = json::array();
    const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    for (size_t m = 0; m < b.doc["materials"].size(); ++m)
      primitives.push_back({{"attributes", {{"POSITION", pos}}}, {"material", m}});
    b.scene({b.node({{"mesh", b.mesh(primitives)}})});
    return loadCapturing(b.writeGltf(dir_), warnings);
  }

  // The message of the mixtrace::Error that loading `path` must throw ("" when none was thrown).
  std::string loadError(const std::string& path) {
    std::string warnings;
    try {
      loadCapturing(path, warnings);
    } catch (const mixtrace::Error& e) {
      return e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "threw a non-mixtrace exception: " << e.what();
      return e.what();
    }
    ADD_FAILURE() << path << " loaded without an error";
    return "";
  }

  static void expectOneLine(const std::string& message) {
    EXPECT_FALSE(message.empty());
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }

  fs::path dir_;
};

void expectVec3(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

glm::vec3 faceNormal(const mixtrace::Triangle& t) {
  return glm::normalize(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
}

// --- Geometry ----------------------------------------------------------------------------------

TEST_F(GltfLoaderTest, LoadsIndexedTrianglesWithEveryIndexWidthAndNonIndexed) {
  const std::vector<glm::vec3> quad = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<uint32_t> order = {0, 1, 2, 1, 3, 2};
  for (int variant = 0; variant < 4; ++variant) {
    SCOPED_TRACE(variant);
    GltfBuilder b;
    json primitive;
    if (variant == 3) {
      std::vector<glm::vec3> flat;
      for (uint32_t i : order) flat.push_back(quad[i]);
      primitive = {{"attributes", {{"POSITION", b.vec3s(flat)}}}};
    } else {
      primitive = {{"attributes", {{"POSITION", b.vec3s(quad)}}}};
      if (variant == 0) primitive["indices"] = b.scalars(std::vector<uint8_t>(order.begin(), order.end()), kUByte);
      if (variant == 1) primitive["indices"] = b.scalars(std::vector<uint16_t>(order.begin(), order.end()), kUShort);
      if (variant == 2) primitive["indices"] = b.scalars(order, kUInt);
    }
    b.scene({b.node({{"mesh", b.mesh(json::array({primitive}))}})});
    const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_, "v" + std::to_string(variant) + ".gltf"));

    ASSERT_EQ(scene.triangles.size(), 2u);
    for (size_t t = 0; t < 2; ++t) {
      for (int k = 0; k < 3; ++k) {
        expectVec3(scene.triangles[t].p[k], quad[order[t * 3 + k]]);
        expectVec3(scene.triangles[t].n[k], {0, 0, 1});  // computed: CCW seen from +Z
        EXPECT_EQ(scene.triangles[t].uv[k], glm::vec2(0.0f));
      }
    }
    EXPECT_EQ(scene.name, "v" + std::to_string(variant) + ".gltf");
    expectVec3(scene.bounds.min, {0, 0, 0});
    expectVec3(scene.bounds.max, {1, 1, 0});
    EXPECT_FALSE(scene.camera.fromFile);
  }
}

TEST_F(GltfLoaderTest, ReadsInterleavedAttributesThroughByteStride) {
  // Per vertex: position (12 bytes), normal (12), uv (8), 4 bytes padding: stride 36.
  struct Vertex {
    float p[3], n[3], uv[2], pad;
  };
  const float s = std::sqrt(0.5f);
  const std::vector<Vertex> vertices = {{{0, 0, 0}, {0, 0, 1}, {0.0f, 0.25f}, -7.0f},
                                        {{2, 0, 0}, {s, 0, s}, {1.0f, 0.5f}, -7.0f},
                                        {{0, 3, 0}, {0, s, s}, {0.75f, 1.0f}, -7.0f}};
  GltfBuilder b;
  const int view = b.view(vertices.data(), vertices.size() * sizeof(Vertex), sizeof(Vertex));
  const int pos = b.accessor(view, kFloat, 3, "VEC3", 0);
  const int nrm = b.accessor(view, kFloat, 3, "VEC3", 12);
  const int uv = b.accessor(view, kFloat, 3, "VEC2", 24);
  const json attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}};
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", attributes}}}))}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));

  ASSERT_EQ(scene.triangles.size(), 1u);
  const auto& t = scene.triangles[0];
  for (int k = 0; k < 3; ++k) {
    expectVec3(t.p[k], {vertices[k].p[0], vertices[k].p[1], vertices[k].p[2]});
    expectVec3(t.n[k], {vertices[k].n[0], vertices[k].n[1], vertices[k].n[2]});
    EXPECT_FLOAT_EQ(t.uv[k].x, vertices[k].uv[0]);
    EXPECT_FLOAT_EQ(t.uv[k].y, vertices[k].uv[1]);
  }
}

TEST_F(GltfLoaderTest, ReadsNormalizedIntegerTexcoords) {
  for (int componentType : {kUByte, kUShort}) {
    SCOPED_TRACE(componentType);
    GltfBuilder b;
    const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    int uv;
    if (componentType == kUByte) {
      const std::vector<uint8_t> data = {0, 255, 255, 0, 51, 102, 0, 0};  // tightly packed 2-byte elements
      uv = b.accessor(b.view(data.data(), data.size(), 0), kUByte, 3, "VEC2", 0, true);
    } else {
      const std::vector<uint16_t> data = {0, 65535, 65535, 0, 13107, 26214};
      uv = b.accessor(b.view(data.data(), data.size() * 2), kUShort, 3, "VEC2", 0, true);
    }
    b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}}}))}})});
    const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
    ASSERT_EQ(scene.triangles.size(), 1u);
    const auto& t = scene.triangles[0];
    EXPECT_NEAR(t.uv[0].x, 0.0f, 1e-6f);
    EXPECT_NEAR(t.uv[0].y, 1.0f, 1e-6f);
    EXPECT_NEAR(t.uv[1].x, 1.0f, 1e-6f);
    EXPECT_NEAR(t.uv[1].y, 0.0f, 1e-6f);
    EXPECT_NEAR(t.uv[2].x, 0.2f, 1e-6f);
    EXPECT_NEAR(t.uv[2].y, 0.4f, 1e-6f);
  }
}

TEST_F(GltfLoaderTest, ComputesMissingNormalsOnTheCounterClockwiseSide) {
  GltfBuilder b;
  // Counter-clockwise seen from -X: the front face looks down -X.
  const int pos = b.vec3s({{0, 0, 0}, {0, 0, 1}, {0, 1, 0}});
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}}}))}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
  ASSERT_EQ(scene.triangles.size(), 1u);
  for (int k = 0; k < 3; ++k) expectVec3(scene.triangles[0].n[k], {-1, 0, 0});
}

TEST_F(GltfLoaderTest, AppliesNestedTrsTransformsToPositionsAndNormals) {
  GltfBuilder b;
  const float s = std::sqrt(0.5f);
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3s({{s, s, 0}, {0, 0, 1}, {0, 0, 1}});
  const int mesh = b.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}}));
  const int child = b.node({{"mesh", mesh}, {"scale", {2, 1, 1}}});
  // Parent: translate (1,2,3) after a 90 degree rotation about +Z.
  const int parent = b.node({{"children", {child}}, {"translation", {1, 2, 3}}, {"rotation", {0, 0, s, s}}});
  b.scene({parent});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));

  ASSERT_EQ(scene.triangles.size(), 1u);
  const auto& t = scene.triangles[0];
  // p -> scale (2,1,1) -> rotate z 90: (x,y) -> (-y,x) -> translate.
  expectVec3(t.p[0], {1, 2, 3});
  expectVec3(t.p[1], {1, 4, 3});
  expectVec3(t.p[2], {0, 2, 3});
  // Normal (1,1,0)/sqrt2 under the inverse transpose: scale (1/2,1,1) -> (0.5,1,0), normalised,
  // then rotated to (-1, 0.5, 0) / |.|.
  expectVec3(t.n[0], glm::normalize(glm::vec3(-1.0f, 0.5f, 0.0f)));
  expectVec3(t.n[1], {0, 0, 1});
  expectVec3(scene.bounds.min, {0, 2, 3});
  expectVec3(scene.bounds.max, {1, 4, 3});
}

TEST_F(GltfLoaderTest, AppliesANodeMatrixUnderATranslatedParent) {
  GltfBuilder b;
  // Column-major: rotation of 90 degrees about +X (y -> z, z -> -y), then translation (0,0,-2).
  const std::vector<double> matrix = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, -2, 1};
  const int child = b.node({{"mesh", b.triangleMesh()}, {"matrix", matrix}});
  b.scene({b.node({{"children", {child}}, {"translation", {10, 0, 0}}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
  ASSERT_EQ(scene.triangles.size(), 1u);
  const auto& t = scene.triangles[0];
  expectVec3(t.p[0], {10, 0, -2});
  expectVec3(t.p[1], {11, 0, -2});
  expectVec3(t.p[2], {10, 0, -1});
  for (int k = 0; k < 3; ++k) expectVec3(t.n[k], {0, -1, 0});  // +Z rotated about X
}

TEST_F(GltfLoaderTest, GivesEachPrimitiveInstanceItsOwnId) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const json primitive = {{"attributes", {{"POSITION", pos}}}};
  const int twoPrimitives = b.mesh(json::array({primitive, primitive}));
  b.scene({b.node({{"mesh", twoPrimitives}}), b.node({{"mesh", twoPrimitives}, {"translation", {5, 0, 0}}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));

  ASSERT_EQ(scene.triangles.size(), 4u);
  std::set<uint32_t> ids;
  for (const auto& t : scene.triangles) ids.insert(t.primitive);
  EXPECT_EQ(ids.size(), 4u);
  // The second instance is really placed by its own node.
  EXPECT_FLOAT_EQ(scene.triangles[2].p[0].x, 5.0f);
  EXPECT_NE(scene.triangles[0].primitive, scene.triangles[2].primitive);
}

TEST_F(GltfLoaderTest, NegativeScaleKeepsWindingConsistentWithNormals) {
  GltfBuilder b;
  const float s = std::sqrt(0.5f);
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3s({{0, 0, 1}, {s, 0, s}, {0, 0, 1}});
  const int withNormals = b.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}}));
  const int withoutNormals = b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}}}));
  b.scene({b.node({{"mesh", withNormals}, {"scale", {-1, 1, 1}}}),
           b.node({{"mesh", withoutNormals}, {"scale", {-1, 1, 1}}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));

  ASSERT_EQ(scene.triangles.size(), 2u);
  for (const auto& t : scene.triangles) {
    // Mirroring in X keeps the face pointing +Z; the vertex order must agree with it.
    expectVec3(faceNormal(t), {0, 0, 1});
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(faceNormal(t), t.n[k]), 0.5f);
    std::set<float> xs = {t.p[0].x, t.p[1].x, t.p[2].x};
    EXPECT_EQ(*xs.begin(), -1.0f);  // really mirrored
  }
  // The tilted normal (1,0,1)/sqrt2 mirrors to (-1,0,1)/sqrt2 and stays with its vertex.
  const auto& t = scene.triangles[0];
  bool found = false;
  for (int k = 0; k < 3; ++k) {
    if (t.p[k] == glm::vec3(-1, 0, 0)) {
      expectVec3(t.n[k], {-s, 0, s});
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST_F(GltfLoaderTest, DropsAndReportsDegenerateTriangles) {
  GltfBuilder b;
  const float nan = std::nanf("");
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0},      // good
                           {0, 0, 0}, {1, 1, 1}, {2, 2, 2},      // collinear: zero area
                           {0, 0, 0}, {nan, 0, 0}, {0, 1, 0}});  // non-finite
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}}}))}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_NE(warnings.find("dropped 2 degenerate"), std::string::npos) << warnings;
  EXPECT_TRUE(std::isfinite(scene.bounds.max.x));
}

TEST_F(GltfLoaderTest, SkipsNonTriangleModesWithAWarning) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 1}},
                                                 {{"attributes", {{"POSITION", pos}}}}}))}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_EQ(scene.triangles.size(), 1u);
  EXPECT_NE(warnings.find("mode 1"), std::string::npos) << warnings;
}

// Strips and fans are unrolled with the specification's winding (3.7.2.1): a strip of four
// vertices is two triangles, a fan of five is three, and every one faces +Z like its first; with
// indices and without.
TEST_F(GltfLoaderTest, UnrollsTriangleStripsAndFansKeepingTheirWinding) {
  GltfBuilder b;
  const int strip = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  const int fan = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
  const int fanIndices = b.scalars(std::vector<uint16_t>{0, 1, 2, 3, 4}, kUShort);
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", strip}}}, {"mode", 5}},
                                                 {{"attributes", {{"POSITION", fan}}}, {"mode", 6}, {"indices", fanIndices}}}))}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 5u) << warnings;
  for (const mixtrace::Triangle& t : scene.triangles) expectVec3(faceNormal(t), {0, 0, 1});
  expectVec3(scene.triangles[1].p[0], {1, 0, 0});   // strip triangle 1 = {v1, v3, v2}
  expectVec3(scene.triangles[1].p[1], {1, 1, 0});
  expectVec3(scene.triangles[4].p[2], {0, 0, 0});   // fan triangle 2 = {v3, v4, v0}
  EXPECT_EQ(warnings.find("mode"), std::string::npos) << warnings;
}

// KHR_mesh_quantization: SHORT positions (padded to 8-byte elements) dequantized by the node's
// scale, normalized BYTE normals, normalized SHORT texture coordinates. Without the extension the
// same file is refused, naming it.
TEST_F(GltfLoaderTest, ReadsQuantizedAttributesUnderKhrMeshQuantization) {
  constexpr int kByte = 5120, kShort = 5122;
  GltfBuilder b;
  const std::vector<int16_t> positions = {0, 0, 0, 0, 100, 0, 0, 0, 0, 100, 0, 0};
  const std::vector<int8_t> normals = {0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0};
  const std::vector<int16_t> uvs = {0, 0, 32767, 0, 0, -32767};
  const int p = b.accessor(b.view(positions.data(), positions.size() * 2, 8), kShort, 3, "VEC3");
  const int n = b.accessor(b.view(normals.data(), normals.size(), 4), kByte, 3, "VEC3", 0, true);
  const int t = b.accessor(b.view(uvs.data(), uvs.size() * 2), kShort, 3, "VEC2", 0, true);
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}}}}))},
                   {"scale", {0.01, 0.01, 0.01}}})});
  const std::string plain = loadError(b.writeGltf(dir_, "plain.gltf"));
  expectOneLine(plain);
  EXPECT_NE(plain.find("KHR_mesh_quantization"), std::string::npos) << plain;

  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 1u) << warnings;
  const mixtrace::Triangle& tri = scene.triangles[0];
  expectVec3(tri.p[1], {1, 0, 0});
  expectVec3(tri.p[2], {0, 1, 0});
  for (int k = 0; k < 3; ++k) expectVec3(tri.n[k], {0, 0, 1});
  EXPECT_NEAR(tri.uv[1].x, 1.0f, 1e-6f);
  EXPECT_NEAR(tri.uv[2].y, -1.0f, 1e-6f);
  EXPECT_EQ(warnings.find("KHR_mesh_quantization"), std::string::npos) << "supported, not warned about: " << warnings;
}

// --- Materials and textures --------------------------------------------------------------------

TEST_F(GltfLoaderTest, ConvertsMaterialFactorsEmissiveStrengthAndDefaults) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.doc["materials"] = json::array(
      {{{"pbrMetallicRoughness",
         {{"baseColorFactor", {0.2, 0.4, 0.6, 0.5}}, {"metallicFactor", 0.3}, {"roughnessFactor", 0.7}}},
        {"emissiveFactor", {1.0, 0.5, 0.25}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
        {"doubleSided", true}},
       {{"name", "all defaults"}}});
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"material", 0}},
                                                 {{"attributes", {{"POSITION", pos}}}, {"material", 1}},
                                                 {{"attributes", {{"POSITION", pos}}}}}))}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_EQ(warnings.find("unsupported"), std::string::npos) << warnings;

  ASSERT_EQ(scene.triangles.size(), 3u);
  const mixtrace::MaterialGpu& m0 = scene.materials.at(scene.triangles[0].material);
  expectVec3(m0.baseColor, {0.2f, 0.4f, 0.6f});
  EXPECT_FLOAT_EQ(m0.metallic, 0.3f);
  EXPECT_FLOAT_EQ(m0.roughness, 0.7f);
  expectVec3(m0.emission, {4.0f, 2.0f, 1.0f});
  EXPECT_EQ(m0.flags & mixtrace::shared::kMaterialDoubleSided, mixtrace::shared::kMaterialDoubleSided);
  EXPECT_EQ(m0.baseColorTexture, -1);
  EXPECT_EQ(m0.metallicRoughnessTexture, -1);
  EXPECT_EQ(m0.emissiveTexture, -1);

  for (size_t t : {1u, 2u}) {  // material without factors, and no material at all: spec defaults
    const mixtrace::MaterialGpu& m = scene.materials.at(scene.triangles[t].material);
    expectVec3(m.baseColor, {1, 1, 1});
    EXPECT_FLOAT_EQ(m.metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.roughness, 1.0f);
    expectVec3(m.emission, {0, 0, 0});
    EXPECT_EQ(m.flags, 0u);
    EXPECT_EQ(m.baseColorTexture, -1);
  }
  EXPECT_NE(scene.triangles[0].material, scene.triangles[2].material);
}

std::vector<uint8_t> encodePng(int width, int height, int components, const std::vector<uint8_t>& pixels) {
  std::vector<uint8_t> png;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
      },
      &png, width, height, components, pixels.data(), width * components);
  return png;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST_F(GltfLoaderTest, DecodesTexturesWithWrapModesFiltersAndDeduplicates) {
  // 2x2 RGBA, top row first: red, half-transparent green / blue, grey 188.
  const std::vector<uint8_t> rgba = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255, 188, 188, 188, 255};
  const std::vector<uint8_t> png = encodePng(2, 2, 4, rgba);
  // A 1x1 RGB PNG as an external file next to the .gltf.
  writeBytes(dir_ / "tex.png", encodePng(1, 1, 3, {10, 20, 30}));

  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int uv = b.vec2s({{0, 0}, {1, 0}, {0, 1}});
  const int pngView = b.view(png.data(), png.size());
  b.doc["images"] = json::array({{{"bufferView", pngView}, {"mimeType", "image/png"}}, {{"uri", "tex.png"}}});
  b.doc["samplers"] = json::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 1}}});
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness",
                                      {{"baseColorTexture", {{"index", 0}}},
                                       {"metallicRoughnessTexture", {{"index", 1}}}}},
                                     {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
                                     {"emissiveFactor", {1, 1, 1}}}});
  const json primitive = {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"material", 0}};
  b.scene({b.node({{"mesh", b.mesh(json::array({primitive}))}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_NE(warnings.find("TEXCOORD_1"), std::string::npos) << warnings;

  ASSERT_EQ(scene.textures.size(), 2u);
  const mixtrace::MaterialGpu& m = scene.materials.at(scene.triangles.at(0).material);
  ASSERT_GE(m.baseColorTexture, 0);
  EXPECT_EQ(m.emissiveTexture, m.baseColorTexture);  // same glTF texture -> one Texture
  ASSERT_GE(m.metallicRoughnessTexture, 0);
  EXPECT_NE(m.metallicRoughnessTexture, m.baseColorTexture);

  const mixtrace::Texture& color = scene.textures[size_t(m.baseColorTexture)];
  EXPECT_EQ(color.width, 2u);
  EXPECT_EQ(color.height, 2u);
  EXPECT_EQ(color.wrapS, mixtrace::shared::kWrapClamp);
  EXPECT_EQ(color.wrapT, mixtrace::shared::kWrapMirror);
  EXPECT_TRUE(color.nearest);  // magFilter NEAREST
  ASSERT_EQ(color.texels.size(), 4u);
  EXPECT_EQ(color.texels[0], 0xFF0000FFu);  // red: R in the low byte
  EXPECT_EQ(color.texels[1], 0x8000FF00u);  // green, alpha 128
  EXPECT_EQ(color.texels[2], 0xFFFF0000u);  // blue
  EXPECT_EQ(color.texels[3], 0xFFBCBCBCu);  // grey 188
  const double grey = srgbToLinear(188.0 / 255.0);
  EXPECT_NEAR(color.averageLinear.x, (1.0 + grey) / 4.0, 1e-5);
  EXPECT_NEAR(color.averageLinear.y, (1.0 + grey) / 4.0, 1e-5);
  EXPECT_NEAR(color.averageLinear.z, (1.0 + grey) / 4.0, 1e-5);

  const mixtrace::Texture& external = scene.textures[size_t(m.metallicRoughnessTexture)];
  EXPECT_EQ(external.wrapS, mixtrace::shared::kWrapRepeat);  // no sampler
  EXPECT_EQ(external.wrapT, mixtrace::shared::kWrapRepeat);
  EXPECT_FALSE(external.nearest);  // no sampler: bilinear
  ASSERT_EQ(external.texels.size(), 1u);
  EXPECT_EQ(external.texels[0], 0xFF1E140Au);  // RGB expanded with opaque alpha
  EXPECT_NEAR(external.averageLinear.z, srgbToLinear(30.0 / 255.0), 1e-6);
}

// A 16-bit greyscale PNG, which stb_image_write cannot produce: uncompressed ("stored") deflate
// blocks inside a zlib stream are enough for a valid file.
uint32_t crc32(const std::vector<uint8_t>& bytes, size_t begin) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = begin; i < bytes.size(); ++i) {
    crc ^= bytes[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void appendBigEndian32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 3; i >= 0; --i) out.push_back(uint8_t(v >> (8 * i)));
}

void appendPngChunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data) {
  appendBigEndian32(png, uint32_t(data.size()));
  const size_t typeStart = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  appendBigEndian32(png, crc32(png, typeStart));
}

std::vector<uint8_t> encodeGrey16Png(uint32_t width, const std::vector<uint16_t>& row) {
  std::vector<uint8_t> raw = {0};  // filter type "none" for the single row
  for (uint16_t v : row) {
    raw.push_back(uint8_t(v >> 8));  // PNG samples are big-endian
    raw.push_back(uint8_t(v & 0xFF));
  }
  std::vector<uint8_t> zlib = {0x78, 0x01, 0x01, uint8_t(raw.size()), uint8_t(raw.size() >> 8),
                               uint8_t(~raw.size()), uint8_t(~raw.size() >> 8)};
  zlib.insert(zlib.end(), raw.begin(), raw.end());
  uint32_t a = 1, b = 0;
  for (uint8_t byte : raw) {
    a = (a + byte) % 65521u;
    b = (b + a) % 65521u;
  }
  appendBigEndian32(zlib, (b << 16) | a);

  std::vector<uint8_t> header;
  appendBigEndian32(header, width);
  appendBigEndian32(header, 1);
  header.insert(header.end(), {16, 0, 0, 0, 0});  // 16-bit, greyscale, deflate, no filter, no interlace
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  appendPngChunk(png, "IHDR", header);
  appendPngChunk(png, "IDAT", zlib);
  appendPngChunk(png, "IEND", {});
  return png;
}

TEST_F(GltfLoaderTest, ConvertsSixteenBitImagesToEightBits) {
  const std::vector<uint8_t> png = encodeGrey16Png(3, {0xFFFF, 0x8080, 0x1234});
  GltfBuilder b;
  const int pngView = b.view(png.data(), png.size());
  b.doc["images"] = json::array({{{"bufferView", pngView}, {"mimeType", "image/png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.scene({b.node({{"mesh", b.triangleMesh({{"material", 0}})}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
  ASSERT_EQ(scene.textures.size(), 1u);
  const mixtrace::Texture& t = scene.textures[0];
  EXPECT_EQ(t.width, 3u);
  EXPECT_EQ(t.height, 1u);
  ASSERT_EQ(t.texels.size(), 3u);
  EXPECT_EQ(t.texels[0], 0xFFFFFFFFu);
  EXPECT_EQ(t.texels[1], 0xFF808080u);
  EXPECT_EQ(t.texels[2], 0xFF121212u);  // 0x1234 / 257 rounds to 0x12
}

// --- Camera and lights -------------------------------------------------------------------------

TEST_F(GltfLoaderTest, TakesTheFirstPerspectiveCameraFromItsNode) {
  GltfBuilder b;
  const float s = std::sqrt(0.5f);
  b.doc["cameras"] = json::array({{{"type", "orthographic"},
                                   {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                                  {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                                  {{"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.1}}}}});
  const int ortho = b.node({{"camera", 0}});
  // Rotation of +90 degrees about +Y: -Z (the view direction) turns to -X.
  const int persp = b.node({{"camera", 1}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});
  const int later = b.node({{"camera", 2}});
  b.scene({b.node({{"mesh", b.triangleMesh()}}), ortho, b.node({{"children", {persp}}}), later});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_NE(warnings.find("orthographic"), std::string::npos) << warnings;
  ASSERT_TRUE(scene.camera.fromFile);
  expectVec3(scene.camera.position, {1, 2, 3});
  expectVec3(scene.camera.forward, {-1, 0, 0});
  expectVec3(scene.camera.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera.yfov, 0.5f);
}

TEST_F(GltfLoaderTest, LeavesTheCameraToTheRendererWhenTheFileHasNone) {
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
  const mixtrace::Camera defaults;
  EXPECT_FALSE(scene.camera.fromFile);
  EXPECT_EQ(scene.camera.position, defaults.position);
  EXPECT_EQ(scene.camera.forward, defaults.forward);
  EXPECT_EQ(scene.camera.yfov, defaults.yfov);
}

TEST_F(GltfLoaderTest, LoadsPunctualLightsWithDirectionsFromRotations) {
  GltfBuilder b;
  const float s = std::sqrt(0.5f);
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
      {{{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 8.0}, {"range", 3.0}},
       {{"type", "spot"}, {"intensity", 2.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
       {{"type", "directional"}, {"intensity", 3.0}},
       {{"type", "spot"}, {"spot", json::object()}}});
  auto lightNode = [&](int light, json extra) {
    extra["extensions"] = {{"KHR_lights_punctual", {{"light", light}}}};
    return b.node(extra);
  };
  const int point = lightNode(0, {{"translation", {1, 2, 3}}});
  // -90 degrees about +X: -Z turns to -Y (straight down).
  const int spot = lightNode(1, {{"translation", {0, 5, 0}}, {"rotation", {-s, 0, 0, s}}});
  // +90 degrees about +Y: -Z turns to -X; the scaled parent must not change the unit direction.
  const int directional = lightNode(2, {{"rotation", {0, s, 0, s}}});
  const int scaledParent = b.node({{"children", {directional}}, {"scale", {2, 2, 2}}});
  const int defaultSpot = lightNode(3, json::object());
  b.scene({b.node({{"mesh", b.triangleMesh()}}), point, spot, scaledParent, defaultSpot});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_EQ(warnings.find("range"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find("unsupported"), std::string::npos) << warnings;

  ASSERT_EQ(scene.punctualLights.size(), 4u);
  const auto& p = scene.punctualLights[0];
  EXPECT_EQ(p.kind, mixtrace::shared::kLightPoint);
  expectVec3(p.position, {1, 2, 3});
  expectVec3(p.intensity, {8, 4, 2});

  const auto& sp = scene.punctualLights[1];
  EXPECT_EQ(sp.kind, mixtrace::shared::kLightSpot);
  expectVec3(sp.position, {0, 5, 0});
  expectVec3(sp.direction, {0, -1, 0});
  expectVec3(sp.intensity, {2, 2, 2});
  EXPECT_FLOAT_EQ(sp.innerConeAngle, 0.2f);
  EXPECT_FLOAT_EQ(sp.outerConeAngle, 0.6f);

  const auto& d = scene.punctualLights[2];
  EXPECT_EQ(d.kind, mixtrace::shared::kLightDirectional);
  expectVec3(d.direction, {-1, 0, 0});
  expectVec3(d.intensity, {3, 3, 3});

  const auto& ds = scene.punctualLights[3];
  EXPECT_EQ(ds.kind, mixtrace::shared::kLightSpot);
  EXPECT_FLOAT_EQ(ds.innerConeAngle, 0.0f);
  EXPECT_NEAR(ds.outerConeAngle, 0.785398163f, 1e-6f);
  expectVec3(ds.direction, {0, 0, -1});
  expectVec3(ds.intensity, {1, 1, 1});
}

// --- Containers and extensions -----------------------------------------------------------------

TEST_F(GltfLoaderTest, LoadsBinaryGltfDecidedByMagicBytes) {
  GltfBuilder b;
  const int mesh = b.triangleMesh({{"indices", b.scalars(std::vector<uint16_t>{0, 1, 2}, kUShort)}});
  b.scene({b.node({{"mesh", mesh}, {"translation", {0, 0, 4}}})});
  for (const std::string name : {"scene.glb", "binary-named.gltf"}) {
    SCOPED_TRACE(name);
    const Scene scene = mixtrace::loadGltf(b.writeGlb(dir_, name));
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectVec3(scene.triangles[0].p[1], {1, 0, 4});
    EXPECT_EQ(scene.name, name);
  }
  // And JSON is recognised as JSON whatever the extension says.
  const Scene json = mixtrace::loadGltf(b.writeGltf(dir_, "json-named.glb"));
  EXPECT_EQ(json.triangles.size(), 1u);
}

TEST_F(GltfLoaderTest, RefusesRequiredUnsupportedExtensionNamingIt) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  const std::string message = loadError(b.writeGltf(dir_));
  expectOneLine(message);
  EXPECT_NE(message.find("scene.gltf requires unsupported glTF extension KHR_draco_mesh_compression"),
            std::string::npos)
      << message;
}

// A Draco file whose compressed data lives in a file the parser cannot read (here: absent) is
// refused for the extension it requires, not with the parser's "file not found".
TEST_F(GltfLoaderTest, RefusesRequiredUnsupportedExtensionEvenWhenTheParserFailsFirst) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  // The written file with one more buffer, in a file that does not exist.
  auto withMissingBuffer = [&](const std::string& name) {
    const std::string path = b.writeGltf(dir_, name);
    json written = json::parse(std::ifstream(path));
    written["buffers"].push_back({{"uri", "compressed.bin"}, {"byteLength", 64}});
    std::ofstream(path) << written.dump(1);
    return path;
  };
  const std::string message = loadError(withMissingBuffer("scene.gltf"));
  expectOneLine(message);
  EXPECT_NE(message.find("scene.gltf requires unsupported glTF extensions KHR_draco_mesh_compression, "
                         "EXT_meshopt_compression"),
            std::string::npos)
      << message;
  // Without the requirement the parser's own error stands.
  b.doc.erase("extensionsRequired");
  const std::string parserError = loadError(withMissingBuffer("optional.gltf"));
  EXPECT_EQ(parserError.find("requires unsupported"), std::string::npos) << parserError;
  EXPECT_NE(parserError.find("optional.gltf"), std::string::npos) << parserError;
}

// Properties the renderer does not honour are named, each once however often the file uses it
// (two materials with occlusion maps, an animation); what it honours (normal maps, COLOR_0,
// doubleSided, alphaMode) is not named.
TEST_F(GltfLoaderTest, NamesEachIgnoredPropertyOnce) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int colours = b.vec3s({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const json ignoredMaterial = {{"normalTexture", {{"index", 0}}},
                                {"occlusionTexture", {{"index", 0}}},
                                {"alphaMode", "MASK"},
                                {"doubleSided", true}};
  b.doc["materials"] = json::array({ignoredMaterial, ignoredMaterial, {{"alphaMode", "OPAQUE"}}});
  b.doc["textures"] = json::array({json::object()});   // no source: never decoded, only named
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"COLOR_0", colours}}}, {"material", 0}},
                                                 {{"attributes", {{"POSITION", pos}, {"COLOR_0", colours}}}, {"material", 1}},
                                                 {{"attributes", {{"POSITION", pos}}}, {"material", 2}}}))}})});
  b.doc["animations"] = json::array({{{"channels", json::array()}, {"samplers", json::array()}}});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_EQ(scene.triangles.size(), 3u);
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = warnings.find(what); at != std::string::npos; at = warnings.find(what, at + 1)) ++n;
    return n;
  };
  for (const char* property : {"ignoring occlusionTexture: ambient occlusion maps are for rasterizers",
                               "ignoring animations"})
    EXPECT_EQ(count(property), 1u) << property << " in: " << warnings;
  EXPECT_EQ(count("OPAQUE"), 0u) << warnings;
  EXPECT_EQ(count("COLOR_0"), 0u) << warnings;
  EXPECT_EQ(count("MASK"), 0u) << warnings;
}

TEST_F(GltfLoaderTest, WarnsAboutOptionalUnsupportedExtensionAndLoads) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_lights_punctual"};
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  EXPECT_EQ(scene.triangles.size(), 1u);
  EXPECT_NE(warnings.find("KHR_materials_clearcoat"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find("KHR_lights_punctual"), std::string::npos) << warnings;
}

// --- Errors: each a mixtrace::Error with a one-line message naming the file ---------------------

TEST_F(GltfLoaderTest, MalformedJsonIsAnError) {
  const fs::path path = dir_ / "broken.gltf";
  std::ofstream(path) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ {\"mesh\": 0 }\n ,, \n";
  const std::string message = loadError(path.string());
  expectOneLine(message);
  EXPECT_NE(message.find("broken.gltf"), std::string::npos) << message;
}

TEST_F(GltfLoaderTest, NonGltfFileIsAnError) {
  const fs::path path = dir_ / "notes.gltf";
  std::ofstream(path) << "this is not a glTF file\nat all\n";
  const std::string message = loadError(path.string());
  expectOneLine(message);
  EXPECT_NE(message.find("not a glTF"), std::string::npos) << message;
}

TEST_F(GltfLoaderTest, TruncatedGlbIsAnError) {
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  std::vector<uint8_t> bytes = b.glbBytes();
  for (size_t cut : {size_t(10), bytes.size() / 2, size_t(8)}) {
    SCOPED_TRACE(cut);
    std::vector<uint8_t> truncated(bytes.begin(), bytes.end() - long(cut));
    const fs::path path = dir_ / "cut.glb";
    writeBytes(path, truncated);
    const std::string message = loadError(path.string());
    expectOneLine(message);
    EXPECT_NE(message.find("cut.glb"), std::string::npos) << message;
  }
  // A BIN chunk whose declared length runs past the file's declared length.
  std::vector<uint8_t> lying = bytes;
  const size_t binHeader = 20 + (size_t(lying[12]) | size_t(lying[13]) << 8);
  lying[binHeader] += 8;
  writeBytes(dir_ / "lying.glb", lying);
  expectOneLine(loadError((dir_ / "lying.glb").string()));
}

TEST_F(GltfLoaderTest, MissingFileIsAnError) {
  const std::string message = loadError((dir_ / "nowhere.gltf").string());
  expectOneLine(message);
  EXPECT_NE(message.find("nowhere.gltf"), std::string::npos) << message;
}

TEST_F(GltfLoaderTest, BufferShorterThanItsViewsIsAnError) {
  {
    GltfBuilder b;
    b.scene({b.node({{"mesh", b.triangleMesh()}})});
    b.doc["bufferViews"][0]["byteLength"] = 400;  // the buffer holds 36 bytes
    const std::string message = loadError(b.writeGltf(dir_, "view.gltf"));
    expectOneLine(message);
    EXPECT_NE(message.find("bufferView 0"), std::string::npos) << message;
  }
  {
    // The buffer itself declares more bytes than its data URI holds.
    GltfBuilder b;
    b.scene({b.node({{"mesh", b.triangleMesh()}})});
    const std::string path = b.writeGltf(dir_, "buffer.gltf");
    json d;
    std::ifstream(path) >> d;
    d["buffers"][0]["byteLength"] = 4000;
    std::ofstream(path) << d.dump();
    const std::string message = loadError(path);
    expectOneLine(message);
    EXPECT_NE(message.find("buffer.gltf"), std::string::npos) << message;
    EXPECT_EQ(message.find("AAAAAAAA"), std::string::npos) << "the data URI is not quoted: " << message;
  }
}

TEST_F(GltfLoaderTest, AccessorOutOfRangeIsAnError) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  b.doc["accessors"][pos]["count"] = 4;  // one more element than the view holds
  b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", pos}}}}}))}})});
  const std::string message = loadError(b.writeGltf(dir_));
  expectOneLine(message);
  EXPECT_NE(message.find("accessor 0"), std::string::npos) << message;

  GltfBuilder offset;
  const int pos2 = offset.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  offset.doc["accessors"][pos2]["byteOffset"] = 4;
  offset.scene({offset.node({{"mesh", offset.mesh(json::array({{{"attributes", {{"POSITION", pos2}}}}}))}})});
  expectOneLine(loadError(offset.writeGltf(dir_, "offset.gltf")));
}

TEST_F(GltfLoaderTest, IndexOutOfRangeOfVerticesIsAnError) {
  GltfBuilder b;
  const int mesh = b.triangleMesh({{"indices", b.scalars(std::vector<uint16_t>{0, 1, 3}, kUShort)}});
  b.scene({b.node({{"mesh", mesh}})});
  const std::string message = loadError(b.writeGltf(dir_));
  expectOneLine(message);
  EXPECT_NE(message.find("index 3"), std::string::npos) << message;
}

// Sparse storage (glTF 2.0 3.6.2.3, as SimpleSparseAccessor uses it): substitutions over the base
// elements, or over zeros when the accessor has no bufferView.
TEST_F(GltfLoaderTest, SparseAccessorsSubstituteTheirElements) {
  GltfBuilder b;
  const int mesh = b.triangleMesh();   // (0,0,0) (1,0,0) (0,1,0)
  const std::vector<uint8_t> sparseIndex = {1, 0, 0, 0};
  const std::vector<float> sparseValue = {5, 0, 0};
  const int iv = b.view(sparseIndex.data(), sparseIndex.size());
  const int vv = b.view(sparseValue.data(), sparseValue.size() * 4);
  b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
                                     {"values", {{"bufferView", vv}}}};
  // A second primitive from zeros: vertex 1 and 2 substituted (UNSIGNED_SHORT indices, an offset).
  const std::vector<uint16_t> zeroIndices = {7, 1, 2};   // 7: padding before byteOffset 2
  const std::vector<glm::vec3> zeroValues = {{0, 0, 1}, {0, 2, 1}};
  const int ziv = b.view(zeroIndices.data(), zeroIndices.size() * 2);
  const int zvv = b.view(zeroValues.data(), zeroValues.size() * sizeof(glm::vec3));
  b.doc["accessors"].push_back({{"componentType", kFloat}, {"count", 3}, {"type", "VEC3"},
                                {"sparse", {{"count", 2},
                                            {"indices", {{"bufferView", ziv}, {"byteOffset", 2}, {"componentType", kUShort}}},
                                            {"values", {{"bufferView", zvv}}}}}});
  const int zeros = int(b.doc["accessors"].size()) - 1;
  b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", zeros}}}});
  b.scene({b.node({{"mesh", mesh}})});
  const Scene scene = mixtrace::loadGltf(b.writeGltf(dir_));
  ASSERT_EQ(scene.triangles.size(), 2u);
  expectVec3(scene.triangles[0].p[0], {0, 0, 0});
  expectVec3(scene.triangles[0].p[1], {5, 0, 0});   // substituted
  expectVec3(scene.triangles[0].p[2], {0, 1, 0});
  expectVec3(scene.triangles[1].p[0], {0, 0, 0});   // a zero not substituted
  expectVec3(scene.triangles[1].p[1], {0, 0, 1});
  expectVec3(scene.triangles[1].p[2], {0, 2, 1});

  // Indices out of range or not increasing, and values past their view: one-line errors.
  for (const json& bad : {json{{"count", 2}, {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
                               {"values", {{"bufferView", vv}}}},   // values: 2 needed, 1 there
                          json{{"count", 4}, {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
                               {"values", {{"bufferView", zvv}}}},   // more substitutions than elements
                          json{{"count", 2}, {"indices", {{"bufferView", ziv}, {"componentType", kUShort}}},
                               {"values", {{"bufferView", zvv}}}}}) {   // index 7 >= 3
    GltfBuilder c = b;
    c.doc["accessors"][0]["sparse"] = bad;
    const std::string message = loadError(c.writeGltf(dir_, "bad.gltf"));
    expectOneLine(message);
    EXPECT_NE(message.find("sparse"), std::string::npos) << message;
  }
}

TEST_F(GltfLoaderTest, SceneWithoutTrianglesIsAnError) {
  GltfBuilder b;
  b.triangleMesh();  // a mesh exists but no node of the scene uses it
  b.scene({b.node({{"name", "empty"}})});
  const std::string message = loadError(b.writeGltf(dir_));
  expectOneLine(message);
  EXPECT_NE(message.find("contains no triangles"), std::string::npos) << message;
}

TEST_F(GltfLoaderTest, NodeCycleIsAnError) {
  GltfBuilder b;
  const int mesh = b.triangleMesh();
  b.node({{"mesh", mesh}, {"children", {1}}});
  b.node({{"children", {0}}});
  b.scene({0});
  expectOneLine(loadError(b.writeGltf(dir_)));
}

// --- Shipped scenes ----------------------------------------------------------------------------

// The nesting limit (gltf/gltf_limits.h: 128) counts [ and { outside strings only: the document's
// own object is level 1, so extras nested 127 deep load and 128 deep are refused; brackets and
// escaped quotes inside a string do not count.
TEST_F(GltfLoaderTest, NestingLimitCountsBracketsOutsideStringsOnly) {
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangleMesh()}})});
  // The extras go in as raw text: nlohmann::json would refuse to build them this deep itself.
  const auto withExtras = [&](const std::string& extras, const std::string& name) {
    const std::string path = b.writeGltf(dir_, name);
    std::ifstream in(path);
    std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    body.insert(1, "\"extras\": " + extras + ", ");
    std::ofstream(path) << body;
    return path;
  };
  std::string warnings;
  EXPECT_NO_THROW(loadCapturing(withExtras(std::string(127, '[') + std::string(127, ']'), "ok.gltf"), warnings));
  const std::string inString = "\"\\\"" + std::string(1000, '[') + "{\\\\\"";  // "\"[[[...{\\"
  EXPECT_NO_THROW(loadCapturing(withExtras(inString, "string.gltf"), warnings));
  const std::string message = loadError(withExtras(std::string(128, '[') + std::string(128, ']'), "deep.gltf"));
  expectOneLine(message);
  EXPECT_NE(message.find("nests deeper than 128 levels"), std::string::npos) << message;
}

// Float's range is the bound, not some smaller guess: 3e38 loads, 4e38 (and a light beyond it) does not.
TEST_F(GltfLoaderTest, EmissiveStrengthUpToFloatMaxLoadsBeyondIsRefusedByName) {
  for (double strength : {3e38, 4e38}) {
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    b.doc["materials"] = json::array({{{"emissiveFactor", {1, 1, 1}},
                                       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}}});
    b.scene({b.node({{"mesh", b.triangleMesh({{"material", 0}})}})});
    const std::string path = b.writeGltf(dir_, "strength.gltf");
    if (strength < 3.4e38) {
      std::string warnings;
      const Scene scene = loadCapturing(path, warnings);
      EXPECT_FLOAT_EQ(scene.materials.at(0).emission.x, 3e38f);
    } else {
      const std::string message = loadError(path);
      expectOneLine(message);
      EXPECT_NE(message.find("materials[0].emissiveStrength 4e+38 does not fit in a float"), std::string::npos)
          << message;
    }
  }
}

// An accessor without a bufferView is zeros; up to the limit that is valid (degenerate) data.
TEST_F(GltfLoaderTest, AccessorWithoutBufferViewIsBoundedByTheDatalessLimit) {
  for (size_t count : {size_t(3), size_t(1) << 21}) {
    GltfBuilder b;
    const int real = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    b.doc["accessors"].push_back({{"componentType", kFloat}, {"count", count}, {"type", "VEC3"}});
    const int zeros = int(b.doc["accessors"].size()) - 1;
    b.scene({b.node({{"mesh", b.mesh(json::array({{{"attributes", {{"POSITION", real}}}},
                                                   {{"attributes", {{"POSITION", zeros}}}}}))}})});
    const std::string path = b.writeGltf(dir_, "zeros.gltf");
    if (count == 3) {
      std::string warnings;
      EXPECT_EQ(loadCapturing(path, warnings).triangles.size(), 1u);  // the zero triangle is dropped
    } else {
      const std::string message = loadError(path);
      expectOneLine(message);
      EXPECT_NE(message.find("has no bufferView but claims 2097152 elements"), std::string::npos) << message;
    }
  }
}

// Each material's textures read its TEXCOORD set (texCoord, or the KHR_texture_transform's own,
// which overrides it) through its transform: uv' = offset + R (scale uv), R turning the UVs
// counter-clockwise (the extension's example: offset (0, 1), rotation pi/2, scale 0.5 reads the
// lower-left quadrant turned clockwise). Textures of one material that disagree are said.
TEST_F(GltfLoaderTest, MaterialsReadTheirTexCoordSetThroughTheirTextureTransform) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int uv0 = b.vec2s({{0, 0}, {1, 0}, {0, 1}});
  const int uv1 = b.vec2s({{0.25f, 0.5f}, {0.75f, 0.5f}, {0.25f, 1.0f}});
  const std::vector<uint8_t> png = encodePng(1, 1, 3, {10, 20, 30});
  b.doc["images"] = json::array({{{"bufferView", b.view(png.data(), png.size())}, {"mimeType", "image/png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  auto transform = [](const json& t) { return json{{"KHR_texture_transform", t}}; };
  auto baseColor = [](const json& info) { return json{{"pbrMetallicRoughness", {{"baseColorTexture", info}}}}; };
  b.doc["materials"] = json::array({
      baseColor({{"index", 0}, {"texCoord", 1}}),
      baseColor({{"index", 0},
                 {"extensions", transform({{"offset", {0, 1}}, {"rotation", 1.5707963267948966}, {"scale", {0.5, 0.5}}})}}),
      baseColor({{"index", 0}, {"texCoord", 0}, {"extensions", transform({{"texCoord", 1}, {"offset", {0.5, 0}}})}}),
      {{"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", 0}, {"extensions", transform({{"scale", {2, 2}}})}}},
         {"metallicRoughnessTexture", {{"index", 0}}}}}},
      {{"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", 0}, {"extensions", transform({{"scale", {2, 2}}})}}},
         {"metallicRoughnessTexture", {{"index", 0}}}}},
       {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
       {"normalTexture", {{"index", 0}}}},
  });
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  json primitives = json::array();
  for (int m = 0; m < 5; ++m)
    primitives.push_back({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}}, {"material", m}});
  b.scene({b.node({{"mesh", b.mesh(primitives)}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 5u);
  const glm::vec2 expected[4][3] = {
      {{0.25f, 0.5f}, {0.75f, 0.5f}, {0.25f, 1.0f}},  // TEXCOORD_1
      {{0.0f, 1.0f}, {0.0f, 0.5f}, {0.5f, 1.0f}},     // the lower-left quadrant, turned
      {{0.75f, 0.5f}, {1.25f, 0.5f}, {0.75f, 1.0f}},  // the extension's texCoord 1, offset
      {{0.0f, 0.0f}, {2.0f, 0.0f}, {0.0f, 2.0f}},     // the base colour's scale
  };
  for (int m = 0; m < 4; ++m)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(scene.triangles[size_t(m)].uv[k].x, expected[m][k].x, 1e-6f) << "material " << m << " corner " << k;
      EXPECT_NEAR(scene.triangles[size_t(m)].uv[k].y, expected[m][k].y, 1e-6f) << "material " << m << " corner " << k;
    }
  // Material 3's metallic-roughness texture reads TEXCOORD_0 untransformed: the second mapping.
  using mixtrace::shared::kMaterialSecondUvAny;
  using mixtrace::shared::kMaterialSecondUvMetallicRoughness;
  auto materialOf = [&](size_t t) { return scene.materials.at(scene.triangles.at(t).material); };
  for (int m = 0; m < 3; ++m) EXPECT_EQ(materialOf(size_t(m)).flags & kMaterialSecondUvAny, 0u) << "material " << m;
  EXPECT_EQ(materialOf(3).flags & kMaterialSecondUvAny, kMaterialSecondUvMetallicRoughness);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(scene.triangles[3].uv2[k], glm::vec2(k == 1, k == 2)) << "TEXCOORD_0 corner " << k;
  // Material 4: base colour scaled (first), metallic-roughness and normal plain TEXCOORD_0
  // (second), emissive TEXCOORD_1: a third mapping, which the first serves, with a word.
  EXPECT_EQ(materialOf(4).flags & kMaterialSecondUvAny,
            kMaterialSecondUvMetallicRoughness | mixtrace::shared::kMaterialSecondUvNormal);
  EXPECT_NE(warnings.find("material 4's emissiveTexture reads TEXCOORD_1, a third texture-coordinate mapping; the "
                          "baseColorTexture's TEXCOORD_0 through a KHR_texture_transform serves it"),
            std::string::npos)
      << warnings;
  EXPECT_EQ(warnings.find("unsupported"), std::string::npos) << warnings;
  // A set the primitive lacks: said, and the coordinates are (0, 0).
  b.doc["materials"][0] = baseColor({{"index", 0}, {"texCoord", 3}});
  const Scene missing = loadCapturing(b.writeGltf(dir_, "missing.gltf"), warnings);
  EXPECT_NE(warnings.find("has no TEXCOORD_3"), std::string::npos) << warnings;
  EXPECT_EQ(missing.triangles.at(0).uv[1], glm::vec2(0.0f));
}

// COLOR_0 in each of the specification's formats reaches the triangles as linear RGBA (alpha 1 for
// VEC3), clamped to [0, 1]; another format is said and ignored (white).
TEST_F(GltfLoaderTest, ReadsVertexColoursInEveryFormat) {
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int floats = b.vec3s({{0.5f, 0.25f, 2.0f}, {0.0f, 1.0f, 0.0f}, {0.1f, 0.2f, 0.3f}});
  const std::vector<uint8_t> bytes = {255, 0, 0, 128, 0, 255, 0, 255, 0, 0, 51, 0};
  const int ubyte = b.accessor(b.view(bytes.data(), bytes.size()), kUByte, 3, "VEC4", 0, true);
  const std::vector<uint16_t> shorts = {65535, 0, 0, 0, 65535, 0, 13107, 0, 0};
  const int ushort = b.accessor(b.view(shorts.data(), shorts.size() * 2), kUShort, 3, "VEC3", 0, true);
  const int unnormalized = b.accessor(b.view(bytes.data(), bytes.size()), kUByte, 3, "VEC4");
  json primitives = json::array();
  for (int c : {floats, ubyte, ushort, unnormalized})
    primitives.push_back({{"attributes", {{"POSITION", pos}, {"COLOR_0", c}}}});
  b.scene({b.node({{"mesh", b.mesh(primitives)}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 4u);
  auto expectColour = [](const glm::vec4& actual, const glm::vec4& expected) {
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(actual[k], expected[k], 1e-6f) << "channel " << k;
  };
  expectColour(scene.triangles[0].color[0], {0.5f, 0.25f, 1.0f, 1.0f});  // 2.0 clamped
  expectColour(scene.triangles[0].color[2], {0.1f, 0.2f, 0.3f, 1.0f});
  expectColour(scene.triangles[1].color[0], {1.0f, 0.0f, 0.0f, 128.0f / 255.0f});
  expectColour(scene.triangles[1].color[2], {0.0f, 0.0f, 0.2f, 0.0f});
  expectColour(scene.triangles[2].color[2], {0.2f, 0.0f, 0.0f, 1.0f});
  expectColour(scene.triangles[3].color[0], glm::vec4(1.0f));
  EXPECT_NE(warnings.find("COLOR_0 of mesh 0 primitive 3 is neither"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find("ignoring COLOR_0"), std::string::npos) << warnings;
}

// alphaMode: MASK keeps its cutoff (default 0.5), BLEND its factor's alpha, OPAQUE neither; an
// emissive material stays opaque, with a warning.
TEST_F(GltfLoaderTest, ReadsAlphaModesAndCutoffs) {
  GltfBuilder b;
  auto material = [](const char* mode, double alpha, const json& extra = json::object()) {
    json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, alpha}}}}, {"alphaMode", mode}};
    m.update(extra);
    return m;
  };
  b.doc["materials"] = json::array({material("MASK", 0.7, {{"alphaCutoff", 0.25}}), material("MASK", 1.0),
                                    material("BLEND", 0.3), material("OPAQUE", 0.2),
                                    material("BLEND", 0.5, {{"emissiveFactor", {1, 1, 1}}})});
  std::string warnings;
  const Scene scene = loadTrianglePerMaterial(b, warnings);
  auto materialOf = [&](size_t t) { return scene.materials.at(scene.triangles.at(t).material); };
  using mixtrace::shared::kMaterialAlphaBlend;
  using mixtrace::shared::kMaterialAlphaMask;
  EXPECT_EQ(materialOf(0).flags & (kMaterialAlphaMask | kMaterialAlphaBlend), kMaterialAlphaMask);
  EXPECT_FLOAT_EQ(materialOf(0).alphaCutoff, 0.25f);
  EXPECT_FLOAT_EQ(materialOf(0).alpha, 0.7f);
  EXPECT_FLOAT_EQ(materialOf(1).alphaCutoff, 0.5f);
  EXPECT_EQ(materialOf(2).flags & (kMaterialAlphaMask | kMaterialAlphaBlend), kMaterialAlphaBlend);
  EXPECT_FLOAT_EQ(materialOf(2).alpha, 0.3f);
  EXPECT_EQ(materialOf(3).flags & (kMaterialAlphaMask | kMaterialAlphaBlend), 0u);
  EXPECT_EQ(materialOf(4).flags & (kMaterialAlphaMask | kMaterialAlphaBlend), 0u);
  EXPECT_NE(warnings.find("material 4 is emissive with alphaMode BLEND: rendered opaque"), std::string::npos) << warnings;
}

// Glass: KHR_materials_transmission's factor, KHR_materials_ior, and KHR_materials_volume's
// thickness deciding volumetric (thickness > 0) or thin-walled glass; unusable values fall back
// to the defaults with a warning, the volume's attenuation is named as ignored, and a volumetric
// glass of IOR 1 is kept just above it.
TEST_F(GltfLoaderTest, ReadsGlassExtensions) {
  GltfBuilder b;
  auto material = [](const json& extensions) { return json{{"extensions", extensions}}; };
  b.doc["materials"] = json::array(
      {material({{"KHR_materials_transmission", {{"transmissionFactor", 0.8}}},
                 {"KHR_materials_ior", {{"ior", 1.33}}},
                 {"KHR_materials_volume", {{"thicknessFactor", 0.1}, {"attenuationDistance", 2.0}}}}),
       material({{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}),
       material({{"KHR_materials_ior", {{"ior", 0.5}}}}),
       material({{"KHR_materials_transmission", {{"transmissionFactor", 1.7}}},
                 {"KHR_materials_ior", {{"ior", 1.0}}},
                 {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}),
       json::object()});
  b.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"};
  std::string warnings;
  const Scene scene = loadTrianglePerMaterial(b, warnings);
  auto materialOf = [&](size_t t) { return scene.materials.at(scene.triangles.at(t).material); };
  using mixtrace::shared::kMaterialVolumetric;
  EXPECT_FLOAT_EQ(materialOf(0).transmission, 0.8f);
  EXPECT_FLOAT_EQ(materialOf(0).ior, 1.33f);
  EXPECT_EQ(materialOf(0).flags & kMaterialVolumetric, kMaterialVolumetric);
  EXPECT_FLOAT_EQ(materialOf(1).transmission, 1.0f);
  EXPECT_FLOAT_EQ(materialOf(1).ior, 1.5f);
  EXPECT_EQ(materialOf(1).flags & kMaterialVolumetric, 0u) << "no volume: thin-walled";
  EXPECT_FLOAT_EQ(materialOf(2).ior, 1.5f);
  EXPECT_FLOAT_EQ(materialOf(2).transmission, 0.0f);
  EXPECT_FLOAT_EQ(materialOf(3).transmission, 1.0f);
  EXPECT_FLOAT_EQ(materialOf(3).ior, mixtrace::shared::kMinVolumeIor);
  EXPECT_FLOAT_EQ(materialOf(4).transmission, 0.0f);
  EXPECT_FLOAT_EQ(materialOf(4).ior, 1.5f);
  for (const char* expected : {"KHR_materials_ior 0.5", "transmissionFactor outside [0, 1]",
                               "volumetric glass of IOR 1", "ignoring KHR_materials_volume attenuation"})
    EXPECT_NE(warnings.find(expected), std::string::npos) << expected << " in: " << warnings;
  EXPECT_EQ(warnings.find("unsupported glTF extension"), std::string::npos) << warnings;
}

// Tangents for normal mapping: TANGENT as the file gives it, turned by the node (w flipped by a
// mirroring one); without it, generated from the UVs: along +u, w making w cross(n, t) point up
// the image (-v). Only primitives whose material has a normal map get them. The normal map's
// scale is read.
TEST_F(GltfLoaderTest, ReadsOrGeneratesTangentsForNormalMappedMaterials) {
  GltfBuilder b;
  // A unit quad in the XY plane facing +Z, image up (v = 0) at y = 1.
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const int uv = b.vec2s({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int mirroredUv = b.vec2s({{1, 1}, {0, 1}, {0, 0}, {1, 0}});   // u runs along -x
  const int tangent = b.accessor(b.view(std::vector<float>{0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1}.data(), 64),
                                 kFloat, 4, "VEC4");
  const int idx = b.scalars(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUShort);
  const std::vector<uint8_t> png = encodePng(1, 1, 3, {128, 128, 255});
  b.doc["images"] = json::array({{{"bufferView", b.view(png.data(), png.size())}, {"mimeType", "image/png"}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}, {"scale", 0.5}}}}, json::object()});
  auto prim = [&](int uvs, bool withTangent, int material) {
    json attributes = {{"POSITION", pos}, {"TEXCOORD_0", uvs}};
    if (withTangent) attributes["TANGENT"] = tangent;
    return json{{"attributes", attributes}, {"indices", idx}, {"material", material}};
  };
  const int generated = b.mesh(json::array({prim(uv, false, 0)}));
  const int mirrored = b.mesh(json::array({prim(mirroredUv, false, 0)}));
  const int given = b.mesh(json::array({prim(uv, true, 0)}));
  const int plain = b.mesh(json::array({prim(uv, false, 1)}));
  b.scene({b.node({{"mesh", generated}}), b.node({{"mesh", mirrored}}), b.node({{"mesh", given}}),
           b.node({{"mesh", given}, {"scale", {-1, 1, 1}}}), b.node({{"mesh", plain}})});
  std::string warnings;
  const Scene scene = loadCapturing(b.writeGltf(dir_), warnings);
  ASSERT_EQ(scene.triangles.size(), 10u);
  auto expectTangent = [&](size_t triangle, glm::vec4 expected) {
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(scene.triangles[triangle].tangent[k][c], expected[c], 1e-6f) << "triangle " << triangle << " corner " << k;
  };
  expectTangent(0, {1, 0, 0, 1});    // generated: +u is +x, up the image is +y = cross(+z, +x)
  expectTangent(2, {-1, 0, 0, -1});  // mirrored UVs: +u is -x, cross(+z, -x) = -y is down: w = -1
  expectTangent(4, {0, 1, 0, -1});   // the file's
  expectTangent(6, {0, 1, 0, 1});    // the file's under a mirroring node: w flips
  expectTangent(8, {0, 0, 0, 0});    // no normal map: no tangent
  const mixtrace::MaterialGpu& m = scene.materials.at(scene.triangles[0].material);
  EXPECT_GE(m.normalTexture, 0);
  EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
  EXPECT_EQ(warnings.find("normalTexture"), std::string::npos) << warnings;
}

TEST(GltfShippedScenes, EveryShippedSceneLoads) {
  const fs::path scenes = fs::path(MIXTRACE_SOURCE_DIR) / "scenes";
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(scenes, ec)) {
    for (const auto& entry : fs::recursive_directory_iterator(scenes, ec)) {
      const std::string ext = entry.path().extension().string();
      if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
    }
  }
  if (files.empty()) GTEST_SKIP() << "no shipped scenes in " << scenes;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Scene scene = mixtrace::loadGltf(file.string());
    EXPECT_FALSE(scene.triangles.empty());
    EXPECT_TRUE(scene.bounds.valid());
    for (const glm::vec3& corner : {scene.bounds.min, scene.bounds.max}) {
      EXPECT_TRUE(std::isfinite(corner.x) && std::isfinite(corner.y) && std::isfinite(corner.z));
    }
  }
}

}  // namespace
