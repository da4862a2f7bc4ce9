// The hit's material and its textures (shaders/shared/surface.h surfaceMaterial, compiled as C++):
// the one loop over a material's texture slots gives each slot its own texture's value at the
// hit (white where the slot has none, the emissive slot only where the triangle emits), so the
// BSDF and the emission are what one lookup per slot gave; and the emission a ray sees at a hit
// (surfaceEmission) is what light sampling evaluates at the same point (emittedRadianceOf), from
// either side, which the MIS weights of the two techniques rely on.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gltf/gltf_loader.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
namespace surface_material_test {
const mixtrace::PreparedScene* gScene = nullptr;
const std::vector<mixtrace::shared::LightSelectionGpu>* gSelection = nullptr;
}  // namespace surface_material_test
#define SHARED_SCENE (*::surface_material_test::gScene)
#define SHARED_LIGHT_SELECTION (*::surface_material_test::gSelection)
#include "scene/shared_scene_access.h"
#include "support/shipped_scenes.h"

namespace {

using namespace mixtrace;
using glm::vec2;
using glm::vec3;
using glm::vec4;

vec4 slotValue(int texture, vec2 uv, bool srgb) {
  return texture >= 0 ? shared::sampleTexture(texture, uv, srgb) : vec4(1.0f);
}

void expectVec4Eq(vec4 a, vec4 b, const std::string& what) {
  EXPECT_EQ(a.x, b.x) << what;
  EXPECT_EQ(a.y, b.y) << what;
  EXPECT_EQ(a.z, b.z) << what;
  EXPECT_EQ(a.w, b.w) << what;
}

// Every triangle of `scene`, hit at random points from both sides: each slot holds its own
// texture's lookup, bit for bit.
void checkSlots(const PreparedScene& scene) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int texturedSlots = 0;
  for (uint32_t tri = 0; tri < scene.shading.size(); ++tri) {
    for (int k = 0; k < 4; ++k) {
      float u = u01(rng), v = u01(rng);
      if (u + v > 1.0f) { u = 1.0f - u; v = 1.0f - v; }
      const shared::TriangleGeom& g = scene.bvh.triangles[tri];
      const vec3 n = glm::cross(g.e1, g.e2);
      const vec3 dir = (k % 2 == 0 ? -1.0f : 1.0f) * n;   // from the front, then from the back
      const shared::SurfaceHit h = shared::makeSurfaceHit(tri, u, v, dir);
      const shared::SurfaceMaterial sm = shared::surfaceMaterial(h);
      const shared::MaterialGpu& m = scene.scene.materials[h.material];
      const std::string at = "triangle " + std::to_string(tri);
      expectVec4Eq(sm.baseColor, slotValue(m.baseColorTexture, h.uv, true), at + " base colour");
      expectVec4Eq(sm.metallicRoughness, slotValue(m.metallicRoughnessTexture, h.uv, false), at + " metallic-roughness");
      expectVec4Eq(sm.emissive, h.emitter >= 0 ? slotValue(m.emissiveTexture, h.uv, true) : vec4(1.0f), at + " emissive");
      expectVec4Eq(sm.transmission, HAS_TRANSMISSION ? slotValue(m.transmissionTexture, h.uv, false) : vec4(1.0f),
                   at + " transmission");
      texturedSlots += (m.baseColorTexture >= 0) + (m.metallicRoughnessTexture >= 0) + (m.emissiveTexture >= 0) +
                       (m.transmissionTexture >= 0);
      if (h.emitter >= 0) {
        const vec3 atHit = shared::surfaceEmission(h, sm);
        const vec3 sampled = shared::emittedRadianceOf(tri, g, u, v, -dir);
        EXPECT_EQ(atHit.x, sampled.x) << at;
        EXPECT_EQ(atHit.y, sampled.y) << at;
        EXPECT_EQ(atHit.z, sampled.z) << at;
      }
    }
  }
  EXPECT_GT(texturedSlots, 0) << "the scene has no textured slot to check";
}

std::string texturedScene() {
  for (const std::string& s : mixtrace::testing::shippedScenes())
    if (s.find("textured") != std::string::npos) return s;
  return {};
}

// textured.glb: a base-colour texture, a metallic-roughness one (NEAREST) and an emissive one, one
// per material.
TEST(SurfaceMaterial, EachSlotHoldsItsOwnTexturesLookup) {
  const std::string path = texturedScene();
  ASSERT_FALSE(path.empty());
  PreparedScene scene = prepareScene(loadGltf(path));
  const std::vector<shared::LightSelectionGpu> table = buildLightSelection(scene.lights, LightSelection::Power);
  surface_material_test::gScene = &scene;
  surface_material_test::gSelection = &table;
  ASSERT_GE(scene.textures.size(), 3u);
  checkSlots(scene);
}

// The same scene with every material given all four textured slots (transmission switched on), the
// loop takes up to four turns and must not hand one slot's value to another.
TEST(SurfaceMaterial, MaterialsWithEverySlotTexturedKeepTheSlotsApart) {
  const std::string path = texturedScene();
  ASSERT_FALSE(path.empty());
  PreparedScene scene = prepareScene(loadGltf(path));
  ASSERT_GE(scene.textures.size(), 3u);
  for (shared::MaterialGpu& m : scene.scene.materials) {
    m.baseColorTexture = 0;
    m.metallicRoughnessTexture = 1;
    m.emissiveTexture = 2;
    m.transmissionTexture = 1;
  }
  scene.features.transmission = true;   // the transmission slot is read only where the scene has glass
  const std::vector<shared::LightSelectionGpu> table = buildLightSelection(scene.lights, LightSelection::Power);
  surface_material_test::gScene = &scene;
  surface_material_test::gSelection = &table;
  checkSlots(scene);
  // And the BSDF takes its factors times the slots' values.
  const shared::SurfaceHit h = shared::makeSurfaceHit(0, 0.25f, 0.25f, -glm::cross(scene.bvh.triangles[0].e1, scene.bvh.triangles[0].e2));
  const shared::SurfaceMaterial sm = shared::surfaceMaterial(h);
  const shared::MaterialGpu& m = scene.scene.materials[h.material];
  const shared::BsdfParams p = shared::surfaceBsdf(h, sm);
  const shared::BsdfParams expected = shared::makeBsdfParams(
      m.baseColor * vec3(h.vertexColor) * vec3(sm.baseColor), m.metallic * sm.metallicRoughness.z,
      m.roughness * sm.metallicRoughness.y);
  EXPECT_EQ(p.baseColor.x, expected.baseColor.x);
  EXPECT_EQ(p.baseColor.y, expected.baseColor.y);
  EXPECT_EQ(p.baseColor.z, expected.baseColor.z);
}

}  // namespace
