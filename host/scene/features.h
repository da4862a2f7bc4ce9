#pragma once
// The effects a scene calls for. Pipelines are specialised on it (specialization constants in
// shaders/shared/bindings.h), so code a scene does not need is compiled out by the driver.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/light_set.h"
#include "scene/scene.h"

namespace mixtrace {

struct FeatureSet {
  bool textures = true;
  bool areaLights = true;
  bool punctualLights = true;
  bool metals = true;
  bool singleLight = false;
  bool environment = true;
  bool vertexColors = true;
  bool alpha = true;
  bool normalMaps = true;
  bool transmission = true;
  bool secondUvs = true;   // a material's textures read two texture-coordinate mappings

  // Everything on: the fully general pipelines (--general-pipelines).
  static FeatureSet general() { return FeatureSet{}; }
  std::vector<uint32_t> specialization() const;  // indexed by SPEC_* constant id
  std::string describe() const;                  // e.g. "textures=0 area=1 punctual=0 ..."
};

FeatureSet deriveFeatures(const Scene& scene, const LightSet& lights);

}  // namespace mixtrace
