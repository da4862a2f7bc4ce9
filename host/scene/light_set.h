#pragma once
// The lights of a scene as the GPU (and the CPU code) sample them: one light per emissive
// primitive instance (its triangles are emitters chosen by area * radiance), the punctual
// lights and, last, the environment. How a method picks among them is not part of the set (scene/light_selection.h).
#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "shared/layouts.h"

namespace mixtrace {

struct LightSet {
  std::vector<shared::LightGpu> lights;
  std::vector<shared::EmitterGpu> emitters;
  std::vector<int32_t> triangleEmitter;  // per BVH-order triangle: emitter index or -1
  std::vector<double> power;             // per light: emitted power (luminance, W), for reports
  uint32_t zeroPowerPrimitives = 0;      // emissive primitives dropped for having no area
  int32_t environmentLight = -1;         // the environment's light (the last one), -1: none
  bool hasArea() const;
  bool hasPunctual() const;
};

// triangleOrder: BVH order -> scene triangle index (Bvh::triangleOrder).
LightSet buildLightSet(const Scene& scene, const std::vector<uint32_t>& triangleOrder);

// Power of a light in luminance units, as used for power-proportional selection.
double punctualLightPower(const PunctualLight& light, float sceneRadius);

}  // namespace mixtrace
