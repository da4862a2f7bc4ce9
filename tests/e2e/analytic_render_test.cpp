// Analytic render tests: small scenes rendered by the real binary, every pixel compared with a
// value computed independently of the renderer (quadrature with the glTF BRDF as implemented,
// shared::bsdfEval), by a per-pixel z-test on the renderer's own variance estimate with a
// Bonferroni-corrected threshold, and by the same test on the image mean. No reference image.
//
//   WhiteFurnace        emissive sphere seen from its centre, depths 1..5, three materials
//   PlaneUnderEmitter   a plane lit directly (max depth 2) by a large emitting rectangle
//   SphereLight         a plane lit directly by a small tessellated spherical light
//
// Every check also runs against the expectation scaled by 0.95 and 1.05 and must reject it:
// the test demonstrably has the power to see a 5% bias. Each case runs on both backends.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shared/bsdf.h"
#include "support/analytic/direct_lighting.h"
#include "support/analytic/expect_matches.h"
#include "support/analytic/furnace.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/analytic/pinhole.h"
#include "support/analytic/pixel_expectation.h"
#include "support/analytic/pixel_ztest.h"
#include "support/analytic/render.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

const char* const kBackends[] = {"vulkan", "cpu"};
const double kPi = 3.14159265358979323846;

shared::BsdfParams bsdfOf(const MaterialSpec& m) {
  return shared::makeBsdfParams(m.baseColor, m.metallic, m.roughness);
}

fs::path writeScene(const std::string& name, const GltfWriter& writer) {
  const fs::path path = scratchDir("analytic") / (name + ".gltf");
  writeFile(path, writer.json());
  return path;
}

// Removes this process's scene and image files after each test.
template <typename Param>
class AnalyticRender : public ::testing::TestWithParam<Param> {
 protected:
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(scratchDir("analytic"), ignored);
  }
};

// ---------------------------------------------------------------------------------------------
// 1. White furnace: the inside of a closed emissive sphere, camera at its centre.

struct FurnaceMaterial {
  const char* name;
  MaterialSpec spec;
};

const FurnaceMaterial kFurnaceMaterials[] = {
    {"diffuse", {glm::vec3(0.5f), 0.0f, 1.0f, glm::vec3(1.0f, 0.8f, 0.6f), false}},
    {"glossy", {glm::vec3(0.8f), 0.0f, 0.3f, glm::vec3(1.0f, 0.8f, 0.6f), false}},
    {"metal", {glm::vec3(0.95f, 0.7f, 0.4f), 1.0f, 0.5f, glm::vec3(1.0f, 0.8f, 0.6f), false}},
};

struct FurnaceCase {
  int material;
  int depth;
  const char* method;
  const char* backend;
};

void PrintTo(const FurnaceCase& c, std::ostream* os) {
  // Compact and free of spaces: CTest names the discovered cases after it.
  *os << kFurnaceMaterials[c.material].name << "_depth" << c.depth << "_" << c.method << "_" << c.backend;
}

std::vector<FurnaceCase> furnaceCases() {
  // Every material at several depths with both methods, without rendering the full product.
  const FurnaceCase perBackend[] = {
      {0, 1, "pt-uniform", ""}, {0, 2, "pt-power", ""},   {0, 3, "pt-uniform", ""}, {0, 5, "pt-power", ""},
      {1, 3, "pt-power", ""},   {1, 5, "pt-uniform", ""}, {2, 2, "pt-uniform", ""}, {2, 5, "pt-power", ""},
  };
  std::vector<FurnaceCase> all;
  for (const char* backend : kBackends)
    for (FurnaceCase c : perBackend) {
      c.backend = backend;
      all.push_back(c);
    }
  return all;
}

class WhiteFurnace : public AnalyticRender<FurnaceCase> {};

TEST_P(WhiteFurnace, MatchesTheSphereRecursion) {
  const FurnaceCase c = GetParam();
  const FurnaceMaterial& mat = kFurnaceMaterials[c.material];
  // Front faces inwards: emission is one-sided, and the camera sees the inside. The sphere is
  // two primitives (a cap and the rest), i.e. two lights of different power, so uniform and
  // power selection really pick lights differently.
  const std::vector<Tri> sphere = icosphere(glm::dvec3(0.0), 1.0, 3, true);
  std::vector<Tri> cap, rest;
  for (const Tri& t : sphere) (t.centroid().y > 0.6 ? cap : rest).push_back(t);
  GltfWriter writer;
  const int material = writer.addMaterial(mat.spec);
  writer.addMesh(cap, material);
  writer.addMesh(rest, material);
  CameraSpec camera;
  camera.position = glm::dvec3(0.0);
  camera.target = glm::dvec3(0.3, -0.2, -1.0);
  camera.yfov = 1.4;
  writer.setCamera(camera);
  const fs::path scene = writeScene("furnace", writer);

  RenderSettings s;
  s.width = 24;
  s.height = 24;
  s.spp = c.depth >= 5 ? 128 : 256;  // the long paths cost most; 128 spp still resolve 0.1%
  s.maxDepth = c.depth;
  s.method = c.method;
  s.backend = c.backend;
  const RenderedImage img = renderWithVariance(scene, s, scene.parent_path() / "furnace.exr");
  ASSERT_TRUE(img.error.empty()) << img.error;

  // From the centre, a pixel ray meets the flat facet at the cosine of its angle to the facet
  // normal (exactly 1 for the true sphere). The recursion's L_D(mu) is evaluated at that cosine.
  // Those cosines all lie in [0.99, 1], where L_D is tabulated and interpolated linearly.
  const SphereFurnace furnace(bsdfOf(mat.spec), glm::dvec3(mat.spec.emission), c.depth);
  constexpr double kMuLow = 0.99;
  constexpr int kTable = 17;
  std::vector<glm::dvec3> table;
  for (int i = 0; i < kTable; ++i) table.push_back(furnace.radiance(kMuLow + (1.0 - kMuLow) * i / (kTable - 1.0)));
  LabelledScene labelled;
  labelled.add(sphere, 0);
  const Expectation expected = pixelExpectation(camera, s.width, s.height, labelled,
      [&](int, const Hit& h, const Ray& r) {
        const double mu = std::abs(glm::dot(r.direction, sphere[size_t(h.triangle)].normal()));
        if (mu < kMuLow) return furnace.radiance(mu);
        const double at = (mu - kMuLow) / (1.0 - kMuLow) * (kTable - 1.0);
        const int i = std::min(int(at), kTable - 2);
        return table[size_t(i)] + (at - i) * (table[size_t(i) + 1] - table[size_t(i)]);
      });

  // Informational: the naive geometric series Le sum_k rho^k, right only for an energy-conserving
  // Lambertian wall; the glTF BRDF's albedo depends on the angle.
  if (c.material == 0) {
    const double rho = mat.spec.baseColor.x;
    double series = 0.0;
    for (int k = 0; k < c.depth; ++k) series += std::pow(rho, k);
    std::printf("furnace %s depth %d: L_D(1) = %.5f (red), naive Le sum rho^k = %.5f; albedo(mu=1) %.4f, "
                "albedo(mu=0.1) %.4f\n",
                mat.name, c.depth, furnace.radiance(1.0).x, mat.spec.emission.x * series, furnace.albedo(1.0).x,
                furnace.albedo(0.1).x);
  }
  // Tolerance: the tessellated sphere only approximates the chord symmetry behind the recursion.
  // At 4096 spp the image means sit within 4.4e-4 of the expectation (the metal at depth 5
  // deviates most, by -4.4e-4 at z -4: a real tessellation effect); the quadrature itself is
  // converged to 3e-5 (doubling both panel counts).
  expectMatches(img, s.spp, expected, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Cases, WhiteFurnace, ::testing::ValuesIn(furnaceCases()), [](const auto& info) {
  const FurnaceCase& c = info.param;
  std::string method = c.method;
  for (char& ch : method) if (ch == '-') ch = '_';
  return std::string(kFurnaceMaterials[c.material].name) + "_depth" + std::to_string(c.depth) + "_" + method + "_" +
         c.backend;
});

// ---------------------------------------------------------------------------------------------
// Shared by the two direct-lighting scenes: a material and a method, on a backend.

struct DirectCase {
  const char* name;
  MaterialSpec receiver;
  const char* method;
  const char* backend;
};

void PrintTo(const DirectCase& c, std::ostream* os) { *os << c.name << "_" << c.method << "_" << c.backend; }

std::vector<DirectCase> directCases(const std::vector<DirectCase>& perBackend) {
  std::vector<DirectCase> all;
  for (const char* backend : kBackends)
    for (DirectCase c : perBackend) {
      c.backend = backend;
      all.push_back(c);
    }
  return all;
}

std::string directCaseName(const ::testing::TestParamInfo<DirectCase>& info) {
  std::string method = info.param.method;
  for (char& ch : method) if (ch == '-') ch = '_';
  return std::string(info.param.name) + "_" + method + "_" + info.param.backend;
}

// Max depth 2 (emission seen directly plus direct light), small images.
RenderSettings directSettings(const DirectCase& c) {
  RenderSettings s;
  s.width = 48;
  s.height = 36;
  s.spp = 256;
  s.maxDepth = 2;
  s.method = c.method;
  s.backend = c.backend;
  return s;
}

const MaterialSpec kBlackEmitter(glm::vec3 le) { return MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, le, false}; }

// Seen directly, a one-sided emitter shows Le on its front face and nothing on its back; at max
// depth 2 nothing else reaches the camera from it (it cannot light itself: flat or convex).
glm::dvec3 seenEmission(const Tri& t, const Ray& r, glm::dvec3 le) {
  return glm::dot(r.direction, t.normal()) < 0.0 ? le : glm::dvec3(0.0);
}

// ---------------------------------------------------------------------------------------------
// 2. A plane under a large uniform emitter: a rectangle on y = 0 facing up, lit by an emitting
// rectangle at y = 1.2 facing down. The emitter is two primitives (two lights) of different
// area, so the two selection methods differ. The camera sees the plane's far and side edges
// (rays that miss must give exactly 0) but not the emitter.

class PlaneUnderEmitter : public AnalyticRender<DirectCase> {};

TEST_P(PlaneUnderEmitter, MatchesTheDirectLightingIntegral) {
  const DirectCase c = GetParam();
  const glm::vec3 le(2.0f, 1.8f, 1.6f);
  const std::vector<Tri> plane =
      rectangle({-1.5, 0.0, 1.0}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.5}, {0.0, 1.0, 0.0});
  const std::vector<Tri> emitterA =
      rectangle({-1.0, 1.2, -1.5}, {2.0, 0.0, 0.0}, {0.0, 0.0, 0.6}, {0.0, -1.0, 0.0});
  const std::vector<Tri> emitterB =
      rectangle({-1.0, 1.2, -0.9}, {2.0, 0.0, 0.0}, {0.0, 0.0, 1.4}, {0.0, -1.0, 0.0});
  GltfWriter writer;
  writer.addMesh(plane, writer.addMaterial(c.receiver));
  const int emitterMaterial = writer.addMaterial(kBlackEmitter(le));
  writer.addMesh(emitterA, emitterMaterial);
  writer.addMesh(emitterB, emitterMaterial);
  CameraSpec camera;
  camera.position = {0.0, 0.9, 1.6};
  camera.target = {0.0, 0.0, -0.6};
  camera.yfov = 0.785;
  writer.setCamera(camera);
  const fs::path scene = writeScene("plane", writer);

  const RenderSettings s = directSettings(c);
  const RenderedImage img = renderWithVariance(scene, s, scene.parent_path() / "plane.exr");
  ASSERT_TRUE(img.error.empty()) << img.error;

  std::vector<Tri> emitter = emitterA;
  emitter.insert(emitter.end(), emitterB.begin(), emitterB.end());
  const std::vector<EmitterPoint> nodes = emitterNodes(emitter, glm::dvec3(le), 3, 3);
  const shared::BsdfParams bsdf = bsdfOf(c.receiver);
  LabelledScene labelled;
  labelled.add(plane, 0);
  labelled.add(emitter, 1);
  const Expectation expected = pixelExpectation(camera, s.width, s.height, labelled,
      [&](int surface, const Hit& h, const Ray& r) {
        if (surface == 1) return seenEmission(emitter[size_t(h.triangle) - plane.size()], r, glm::dvec3(le));
        return directRadiance(bsdf, h.point, {0.0, 1.0, 0.0}, -r.direction, nodes);
      });
  size_t blank = 0, lit = 0;
  for (size_t p = 0; p < expected.tested.size(); ++p)
    if (expected.tested[p]) (expected.value.rgb[3 * p] == 0.0f ? blank : lit)++;
  // The framing is part of what is tested: some background, mostly plane, edges left out.
  EXPECT_GT(blank, 20u);
  EXPECT_GT(lit, expected.tested.size() / 2);
  std::printf("plane: %zu pixels on the plane, %zu background\n", lit, blank);
  // Tolerance: the quadrature (checked against 16 times as many emitter nodes) and float.
  expectMatches(img, s.spp, expected, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Cases, PlaneUnderEmitter,
                         ::testing::ValuesIn(directCases({
                             {"diffuse", {glm::vec3(0.8f, 0.6f, 0.4f), 0.0f, 1.0f, glm::vec3(0.0f), false}, "pt-uniform", ""},
                             {"diffuse", {glm::vec3(0.8f, 0.6f, 0.4f), 0.0f, 1.0f, glm::vec3(0.0f), false}, "pt-power", ""},
                             {"glossy_metal", {glm::vec3(0.9f, 0.7f, 0.5f), 1.0f, 0.35f, glm::vec3(0.0f), false}, "pt-power", ""},
                         })),
                         directCaseName);

// ---------------------------------------------------------------------------------------------
// 3. A small spherical light (an outward-facing icosphere, one light) above a white plane. The
// camera sees the light itself (Le), the lit plane and the background beyond the plane. With a
// single light the two selection methods are the same estimator, so one method is rendered.

class SphereLight : public AnalyticRender<DirectCase> {};

TEST_P(SphereLight, MatchesTheIrradianceOfItsTriangles) {
  const DirectCase c = GetParam();
  const glm::vec3 le(6.0f, 5.0f, 4.0f);
  const glm::dvec3 centre(0.0, 0.8, 0.0);
  const double radius = 0.3;
  const std::vector<Tri> plane =
      rectangle({-2.0, 0.0, 2.0}, {4.0, 0.0, 0.0}, {0.0, 0.0, -4.0}, {0.0, 1.0, 0.0});
  const std::vector<Tri> sphere = icosphere(centre, radius, 2, false);
  GltfWriter writer;
  writer.addMesh(plane, writer.addMaterial(c.receiver));
  writer.addMesh(sphere, writer.addMaterial(kBlackEmitter(le)));
  CameraSpec camera;
  camera.position = {0.0, 1.3, 2.8};
  camera.target = {0.0, 0.15, 0.0};
  camera.yfov = 0.8;
  writer.setCamera(camera);
  const fs::path scene = writeScene("sphere_light", writer);

  const RenderSettings s = directSettings(c);
  const RenderedImage img = renderWithVariance(scene, s, scene.parent_path() / "sphere_light.exr");
  ASSERT_TRUE(img.error.empty()) << img.error;

  // The light's front faces tile its silhouette once (it is convex), so summing over all its
  // triangles with the one-sided cosine integrates exactly what a point on the plane sees.
  const std::vector<EmitterPoint> nodes = emitterNodes(sphere, glm::dvec3(le), 0, 3);
  const shared::BsdfParams bsdf = bsdfOf(c.receiver);
  LabelledScene labelled;
  labelled.add(plane, 0);
  labelled.add(sphere, 1);
  const Expectation expected = pixelExpectation(camera, s.width, s.height, labelled,
      [&](int surface, const Hit& h, const Ray& r) {
        if (surface == 1) return seenEmission(sphere[size_t(h.triangle) - plane.size()], r, glm::dvec3(le));
        return directRadiance(bsdf, h.point, {0.0, 1.0, 0.0}, -r.direction, nodes);
      });

  // Informational: the ideal sphere's irradiance E = pi Le (r / d)^2 cos(theta) (its horizon does
  // not cut the plane), times the BRDF towards the centre, at the centres of the plane pixels.
  double idealSum = 0.0, exactSum = 0.0;
  size_t onPlane = 0, onLight = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const size_t p = size_t(y) * s.width + x;
      if (!expected.tested[p]) continue;
      const Ray r = cameraRay(camera, s.width, s.height, x + 0.5, y + 0.5);
      const Hit h = closestHit(labelled.triangles, r);
      if (h.triangle < 0) continue;
      if (labelled.surface[size_t(h.triangle)] == 1) {
        ++onLight;
        continue;
      }
      ++onPlane;
      const glm::dvec3 toCentre = centre - h.point;
      const double d = glm::length(toCentre);
      const glm::dvec3 wc = toCentre / d;
      const glm::vec3 wo(float(-r.direction.x), float(-r.direction.z), float(-r.direction.y));  // plane frame: normal = y
      const glm::vec3 wi(float(wc.x), float(wc.z), float(wc.y));
      idealSum += double(shared::bsdfEval(bsdf, wo, wi).x) * kPi * le.x * (radius / d) * (radius / d) * wc.y;
      exactSum += directRadiance(bsdf, h.point, {0.0, 1.0, 0.0}, -r.direction, nodes).x;
    }
  std::printf("sphere light: %zu plane and %zu light pixels; tessellated / ideal sphere (red, plane pixels) = %.4f\n",
              onPlane, onLight, exactSum / idealSum);
  EXPECT_GT(onLight, 4u);
  EXPECT_GT(onPlane, size_t(s.width * s.height) / 2);
  expectMatches(img, s.spp, expected, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Cases, SphereLight,
                         ::testing::ValuesIn(directCases({
                             {"white", {glm::vec3(1.0f), 0.0f, 1.0f, glm::vec3(0.0f), false}, "pt-power", ""},
                         })),
                         directCaseName);

}  // namespace
