#include "scene/features.h"

#include "shared/bindings.h"
#include "shared/constants.h"
#include "shared/layouts.h"

namespace mixtrace {

std::vector<uint32_t> FeatureSet::specialization() const {
  std::vector<uint32_t> v(SPEC_COUNT);
  v[SPEC_HAS_TEXTURES] = textures;
  v[SPEC_HAS_AREA_LIGHTS] = areaLights;
  v[SPEC_HAS_PUNCTUAL_LIGHTS] = punctualLights;
  v[SPEC_HAS_METALS] = metals;
  v[SPEC_SINGLE_LIGHT] = singleLight;
  v[SPEC_HAS_ENVIRONMENT] = environment;
  v[SPEC_HAS_VERTEX_COLORS] = vertexColors;
  v[SPEC_HAS_ALPHA] = alpha;
  v[SPEC_HAS_NORMAL_MAPS] = normalMaps;
  v[SPEC_HAS_TRANSMISSION] = transmission;
  v[SPEC_HAS_SECOND_UVS] = secondUvs;
  return v;
}

std::string FeatureSet::describe() const {
  auto b = [](bool x) { return x ? "1" : "0"; };
  return std::string("textures=") + b(textures) + " area-lights=" + b(areaLights) + " punctual-lights=" +
         b(punctualLights) + " metals=" + b(metals) + " single-light=" + b(singleLight) +
         " environment=" + b(environment) + " vertex-colors=" + b(vertexColors) + " alpha=" + b(alpha) + " normal-maps=" + b(normalMaps) +
         " transmission=" + b(transmission) + " second-uvs=" + b(secondUvs);
}

FeatureSet deriveFeatures(const Scene& scene, const LightSet& lights) {
  FeatureSet f;
  f.textures = false;
  f.metals = false;
  f.alpha = false;
  f.normalMaps = false;
  f.transmission = false;
  f.secondUvs = false;
  for (const MaterialGpu& m : scene.materials) {
    f.textures |= m.baseColorTexture >= 0 || m.metallicRoughnessTexture >= 0 || m.emissiveTexture >= 0 ||
                  m.normalTexture >= 0 || m.transmissionTexture >= 0;
    f.metals |= m.metallic > 0.0f || m.metallicRoughnessTexture >= 0;
    f.alpha |= (m.flags & (shared::kMaterialAlphaMask | shared::kMaterialAlphaBlend)) != 0u;
    f.normalMaps |= m.normalTexture >= 0;
    // An IOR other than the default changes F0 only, but that is read in the same place.
    f.transmission |= m.transmission > 0.0f || m.ior != shared::kDefaultIor;
    f.secondUvs |= (m.flags & shared::kMaterialSecondUvAny) != 0u;
  }
  f.areaLights = lights.hasArea();
  f.punctualLights = lights.hasPunctual();
  f.singleLight = lights.lights.size() == 1;
  f.environment = lights.environmentLight >= 0;
  f.vertexColors = false;
  for (const Triangle& t : scene.triangles)
    for (const glm::vec4& c : t.color) f.vertexColors |= c != glm::vec4(1.0f);
  return f;
}

}  // namespace mixtrace
