#include "scene/light_set.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "scene/environment_distribution.h"
#include "shared/sampling.h"
#include "util/log.h"

namespace mixtrace {
namespace {

double luminance(const glm::vec3& c) { return shared::luminance(c); }

// In double: the float cross product of a triangle 1e-12 across (area 1e-24) squares to 1e-48
// inside length() and underflows to 0, and one 1e15 across overflows, so the light set dropped
// such emitters as "zero area" and scaled scenes rendered black. Radiance is scale invariant; the
// light set must be too, over the whole range of float coordinates.
double triangleArea(const Triangle& t) {
  const glm::dvec3 p0(t.p[0]), p1(t.p[1]), p2(t.p[2]);
  return 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
}

glm::vec3 averageEmission(const Scene& scene, const MaterialGpu& m) {
  glm::vec3 e = m.emission;
  if (m.emissiveTexture >= 0 && size_t(m.emissiveTexture) < scene.textures.size())
    e *= scene.textures[size_t(m.emissiveTexture)].averageLinear;
  return e;
}

}  // namespace

bool LightSet::hasArea() const {
  return std::any_of(lights.begin(), lights.end(), [](const shared::LightGpu& l) { return l.kind == shared::kLightArea; });
}
bool LightSet::hasPunctual() const {
  return std::any_of(lights.begin(), lights.end(), [](const shared::LightGpu& l) {
    return l.kind != shared::kLightArea && l.kind != shared::kLightEnvironment;
  });
}

double punctualLightPower(const PunctualLight& light, float sceneRadius) {
  const double pi = 3.14159265358979323846;
  double i = luminance(light.intensity);
  switch (light.kind) {
    case shared::kLightPoint: return 4.0 * pi * i;
    // Solid angle of the cone halfway between inner and outer angle (pbrt's approximation).
    case shared::kLightSpot: return 2.0 * pi * (1.0 - std::cos(0.5 * (light.innerConeAngle + light.outerConeAngle))) * i;
    default: return pi * double(sceneRadius) * sceneRadius * i;  // irradiance over the scene's disk
  }
}

LightSet buildLightSet(const Scene& scene, const std::vector<uint32_t>& triangleOrder) {
  LightSet set;
  set.triangleEmitter.assign(triangleOrder.size(), -1);

  // Group emissive triangles (BVH order) by primitive instance; std::map keeps a stable order.
  std::map<uint32_t, std::vector<uint32_t>> byPrimitive;
  std::map<uint32_t, bool> primitiveSeen;
  for (uint32_t b = 0; b < triangleOrder.size(); ++b) {
    const Triangle& t = scene.triangles[triangleOrder[b]];
    const MaterialGpu& m = scene.materials[t.material];
    if (luminance(averageEmission(scene, m)) <= 0.0 && glm::length(m.emission) <= 0.0f) continue;
    primitiveSeen[t.primitive] = true;
    const double area = triangleArea(t);
    if (area > 0.0 && std::isfinite(area)) byPrimitive[t.primitive].push_back(b);
  }
  set.zeroPowerPrimitives = uint32_t(primitiveSeen.size() - byPrimitive.size());

  for (auto& [primitive, tris] : byPrimitive) {
    shared::LightGpu light{};
    light.kind = shared::kLightArea;
    light.firstEmitter = uint32_t(set.emitters.size());
    light.emitterCount = uint32_t(tris.size());
    double power = 0.0;
    std::vector<double> triPower;
    for (uint32_t b : tris) {
      const Triangle& t = scene.triangles[triangleOrder[b]];
      const MaterialGpu& m = scene.materials[t.material];
      double area = triangleArea(t);
      double sides = (m.flags & shared::kMaterialDoubleSided) ? 2.0 : 1.0;
      // Every triangle stays samplable (weight floor) even if its average radiance rounds to 0.
      double w = area * std::max(luminance(averageEmission(scene, m)), 1e-12);
      triPower.push_back(w);
      power += w * 3.14159265358979323846 * sides;
    }
    double total = 0.0;
    for (double w : triPower) total += w;
    double cdf = 0.0;
    uint32_t lightIndex = uint32_t(set.lights.size());
    for (size_t i = 0; i < tris.size(); ++i) {
      shared::EmitterGpu e{};
      e.triangle = tris[i];
      e.light = lightIndex;
      e.pmf = float(triPower[i] / total);
      cdf += triPower[i] / total;
      e.cdf = (i + 1 == tris.size()) ? 1.0f : float(cdf);
      set.triangleEmitter[tris[i]] = int32_t(set.emitters.size());
      set.emitters.push_back(e);
    }
    set.lights.push_back(light);
    set.power.push_back(power);
  }

  float sceneRadius = 0.5f * glm::length(scene.bounds.extent());
  for (const PunctualLight& p : scene.punctualLights) {
    double power = punctualLightPower(p, sceneRadius);
    if (!(power > 0.0)) continue;
    shared::LightGpu light{};
    light.kind = p.kind;
    light.position = p.position;
    light.direction = glm::normalize(p.direction);
    light.intensity = p.intensity;
    float cosOuter = std::cos(p.outerConeAngle), cosInner = std::cos(p.innerConeAngle);
    light.spotScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    light.spotOffset = -cosOuter * light.spotScale;
    set.lights.push_back(light);
    set.power.push_back(power);
  }

  // The environment last: one light of its own (its own cluster under CMS, like the reference
  // implementation's), whose power is what crosses a disk of the scene's radius.
  if (scene.environment.present()) {
    const double power = 3.14159265358979323846 * double(sceneRadius) * sceneRadius *
                         environmentLuminanceIntegral(scene.environment);
    if (power > 0.0 && std::isfinite(power)) {
      shared::LightGpu light{};
      light.kind = shared::kLightEnvironment;
      set.environmentLight = int32_t(set.lights.size());
      set.lights.push_back(light);
      set.power.push_back(power);
    } else {
      warn("the environment (" + scene.environment.source + ") is black: it lights nothing");
    }
  }

  if (set.zeroPowerPrimitives > 0)
    warn(std::to_string(set.zeroPowerPrimitives) + " emissive primitive(s) have zero area and emit nothing");
  return set;
}

}  // namespace mixtrace
