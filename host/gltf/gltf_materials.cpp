// glTF materials -> MaterialGpu, converted on first use so unused materials cost nothing.
#include <algorithm>
#include <cmath>

#include "gltf/gltf_internal.h"

namespace mixtrace {
namespace gltf {
namespace {

// A factor from the file: non-finite values fall back to the spec default, the rest is clamped to
// the spec's [0, 1]. Sets `changed` when the file's value was not usable as is.
float unitFactor(double value, float fallback, bool& changed) {
  if (!std::isfinite(value)) {
    changed = true;
    return fallback;
  }
  const double clamped = std::min(std::max(value, 0.0), 1.0);
  if (clamped != value) changed = true;
  return float(clamped);
}

float emissiveStrength(const LoadContext& ctx, const tinygltf::Material& material, int materialIndex) {
  const auto it = material.extensions.find("KHR_materials_emissive_strength");
  if (it == material.extensions.end() || !it->second.IsObject()) return 1.0f;
  const tinygltf::Value& strength = it->second.Get("emissiveStrength");
  if (!strength.IsNumber()) return 1.0f;  // spec default
  const double value = strength.GetNumberAsDouble();
  if (!std::isfinite(value) || value < 0.0) {
    ctx.warning("material " + std::to_string(materialIndex) + " has an invalid emissiveStrength; using 1");
    return 1.0f;
  }
  return checkedFloat(ctx, value, "materials[" + std::to_string(materialIndex) + "].emissiveStrength");
}

MaterialGpu defaultMaterial() {
  // glTF 2.0 spec, "Default Material": white, fully metallic, fully rough, no emission.
  MaterialGpu m{};
  m.baseColor = glm::vec3(1.0f);
  m.metallic = 1.0f;
  m.roughness = 1.0f;
  m.emission = glm::vec3(0.0f);
  m.baseColorTexture = -1;
  m.metallicRoughnessTexture = -1;
  m.emissiveTexture = -1;
  m.flags = 0;
  m.alpha = 1.0f;
  m.alphaCutoff = 0.5f;
  m.normalTexture = -1;
  m.normalScale = 1.0f;
  m.transmission = 0.0f;
  m.transmissionTexture = -1;
  m.ior = shared::kDefaultIor;
  m.padMaterial = 0u;
  return m;
}

// A normal texture's reference as a plain one (its scale is read apart).
tinygltf::TextureInfo asTextureInfo(const tinygltf::NormalTextureInfo& n) {
  tinygltf::TextureInfo info;
  info.index = n.index;
  info.texCoord = n.texCoord;
  info.extensions = n.extensions;
  return info;
}

// The texture coordinates one texture reference reads: its texCoord, and its KHR_texture_transform
// (whose own texCoord overrides the reference's). Values that are not finite numbers are the
// extension's defaults, with a warning.
UvMapping uvMappingOf(const LoadContext& ctx, const tinygltf::TextureInfo& info, const std::string& where) {
  UvMapping m;
  m.set = std::max(info.texCoord, 0);
  const auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return m;
  const tinygltf::Value& t = it->second;
  bool invalid = false;
  auto number = [&](const tinygltf::Value& v, double fallback) {
    if (!v.IsNumber()) return fallback;
    const double x = v.GetNumberAsDouble();
    if (std::isfinite(x) && std::abs(x) < 1e30) return x;
    invalid = true;
    return fallback;
  };
  auto pair = [&](const char* name, glm::dvec2 fallback) {
    const tinygltf::Value& v = t.Get(name);
    if (!v.IsArray()) return fallback;
    if (v.ArrayLen() != 2) {
      invalid = true;
      return fallback;
    }
    return glm::dvec2(number(v.Get(0), fallback.x), number(v.Get(1), fallback.y));
  };
  m.offset = pair("offset", glm::dvec2(0.0));
  m.scale = pair("scale", glm::dvec2(1.0));
  m.rotation = number(t.Get("rotation"), 0.0);
  const tinygltf::Value& texCoord = t.Get("texCoord");
  if (texCoord.IsInt() && texCoord.GetNumberAsInt() >= 0) m.set = texCoord.GetNumberAsInt();
  if (invalid) ctx.warning(where + " has a KHR_texture_transform value that is not a usable number; its default is used");
  return m;
}

}  // namespace

MaterialTable::MaterialTable(const LoadContext& ctx, Scene& scene)
    : ctx_(ctx),
      scene_(scene),
      materialSlots_(ctx.model.materials.size(), -1),
      textureSlots_(ctx.model.textures.size(), -1),
      uvMappings_(ctx.model.materials.size()) {}

bool MaterialTable::hasNormalMap(int gltfMaterial) const {
  return gltfMaterial >= 0 && size_t(gltfMaterial) < ctx_.model.materials.size() &&
         ctx_.model.materials[size_t(gltfMaterial)].normalTexture.index >= 0;
}

MaterialUvs MaterialTable::uvMappingFor(int gltfMaterial) {
  if (gltfMaterial < 0 || size_t(gltfMaterial) >= uvMappings_.size()) return MaterialUvs{};
  if (uvMappings_[size_t(gltfMaterial)]) return *uvMappings_[size_t(gltfMaterial)];
  const tinygltf::Material& src = ctx_.model.materials[size_t(gltfMaterial)];
  const std::string where = "material " + std::to_string(gltfMaterial);
  // The textures the renderer reads, the base colour's first: its mapping is the first; the first
  // texture that reads another is the second; a third mapping falls back to the first, with a word.
  const tinygltf::TextureInfo normal = asTextureInfo(src.normalTexture);
  const tinygltf::TextureInfo transmission = transmissionTextureInfo(src);
  struct Slot {
    const tinygltf::TextureInfo* info;
    const char* name;
    uint32_t bit;
  };
  const Slot slots[] = {
      {&src.pbrMetallicRoughness.baseColorTexture, "baseColorTexture", shared::kMaterialSecondUvBaseColor},
      {&src.pbrMetallicRoughness.metallicRoughnessTexture, "metallicRoughnessTexture",
       shared::kMaterialSecondUvMetallicRoughness},
      {&src.emissiveTexture, "emissiveTexture", shared::kMaterialSecondUvEmissive},
      {&normal, "normalTexture", shared::kMaterialSecondUvNormal},
      {&transmission, "transmissionTexture", shared::kMaterialSecondUvTransmission}};
  MaterialUvs uvs;
  const char* firstSlot = nullptr;
  for (const Slot& slot : slots) {
    if (slot.info->index < 0) continue;
    const UvMapping m = uvMappingOf(ctx_, *slot.info, where + " " + slot.name);
    if (!firstSlot) {
      uvs.first = m;
      firstSlot = slot.name;
    } else if (m == uvs.first) {
      continue;
    } else if (!uvs.second || m == *uvs.second) {
      uvs.second = m;
      uvs.secondSlots |= slot.bit;
    } else {
      auto describe = [](const UvMapping& u) {
        return "TEXCOORD_" + std::to_string(u.set) + (u.identity() ? "" : " through a KHR_texture_transform");
      };
      ctx_.warning(where + "'s " + slot.name + " reads " + describe(m) + ", a third texture-coordinate mapping; the " +
                   firstSlot + "'s " + describe(uvs.first) + " serves it (triangles carry two)");
    }
  }
  uvMappings_[size_t(gltfMaterial)] = uvs;
  return uvs;
}

uint32_t MaterialTable::materialFor(int gltfMaterial) {
  if (gltfMaterial < 0) {
    if (defaultMaterial_ < 0) {
      defaultMaterial_ = int(scene_.materials.size());
      scene_.materials.push_back(defaultMaterial());
    }
    return uint32_t(defaultMaterial_);
  }
  if (size_t(gltfMaterial) >= materialSlots_.size()) {
    ctx_.fail("material " + std::to_string(gltfMaterial) + " is referenced but does not exist");
  }
  if (materialSlots_[size_t(gltfMaterial)] >= 0) return uint32_t(materialSlots_[size_t(gltfMaterial)]);

  const tinygltf::Material& src = ctx_.model.materials[size_t(gltfMaterial)];
  const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
  MaterialGpu m = defaultMaterial();
  bool changed = false;
  if (pbr.baseColorFactor.size() >= 4) m.alpha = unitFactor(pbr.baseColorFactor[3], 1.0f, changed);
  if (pbr.baseColorFactor.size() >= 3) {
    m.baseColor = glm::vec3(unitFactor(pbr.baseColorFactor[0], 1.0f, changed),
                            unitFactor(pbr.baseColorFactor[1], 1.0f, changed),
                            unitFactor(pbr.baseColorFactor[2], 1.0f, changed));
  }
  m.metallic = unitFactor(pbr.metallicFactor, 1.0f, changed);
  m.roughness = unitFactor(pbr.roughnessFactor, 1.0f, changed);
  if (src.emissiveFactor.size() == 3) {
    m.emission = glm::vec3(unitFactor(src.emissiveFactor[0], 0.0f, changed),
                           unitFactor(src.emissiveFactor[1], 0.0f, changed),
                           unitFactor(src.emissiveFactor[2], 0.0f, changed));
  }
  if (changed) ctx_.warning("material " + std::to_string(gltfMaterial) + " has factors outside [0, 1]; clamped");
  m.emission *= emissiveStrength(ctx_, src, gltfMaterial);
  m.baseColorTexture = textureFor(pbr.baseColorTexture, gltfMaterial, "baseColorTexture");
  m.metallicRoughnessTexture = textureFor(pbr.metallicRoughnessTexture, gltfMaterial, "metallicRoughnessTexture");
  m.emissiveTexture = textureFor(src.emissiveTexture, gltfMaterial, "emissiveTexture");
  m.normalTexture = textureFor(asTextureInfo(src.normalTexture), gltfMaterial, "normalTexture");
  if (m.normalTexture >= 0) {
    const double scale = src.normalTexture.scale;
    if (std::isfinite(scale) && std::abs(scale) < 1e6) m.normalScale = float(scale);
    else ctx_.warning("material " + std::to_string(gltfMaterial) + " has an invalid normalTexture scale; using 1");
  }
  m.flags = src.doubleSided ? shared::kMaterialDoubleSided : 0u;
  m.flags |= uvMappingFor(gltfMaterial).secondSlots;
  const GlassParameters glass = readGlass(ctx_, src, gltfMaterial);
  m.ior = glass.ior;
  m.transmission = glass.transmission;
  if (glass.volumetric) m.flags |= shared::kMaterialVolumetric;
  if (m.transmission > 0.0f)
    m.transmissionTexture = textureFor(transmissionTextureInfo(src), gltfMaterial, "transmissionTexture");
  if (src.alphaMode == "MASK" || src.alphaMode == "BLEND") {
    const bool emissive = m.emission != glm::vec3(0.0f);
    if (emissive) {
      // A light's sampled points would have to see the same cut-outs as the rays that hit it;
      // rendered opaque instead, and said.
      ctx_.warning("material " + std::to_string(gltfMaterial) + " is emissive with alphaMode " + src.alphaMode +
                   ": rendered opaque (alpha on lights is not supported)");
    } else {
      m.flags |= src.alphaMode == "MASK" ? shared::kMaterialAlphaMask : shared::kMaterialAlphaBlend;
    }
    if (src.alphaMode == "MASK") {
      const double cutoff = src.alphaCutoff;
      if (std::isfinite(cutoff) && cutoff >= 0.0) m.alphaCutoff = float(std::min(cutoff, 1.0));
      else ctx_.warning("material " + std::to_string(gltfMaterial) + " has an invalid alphaCutoff; using 0.5");
    }
  }
  warnIgnoredProperties(src);

  materialSlots_[size_t(gltfMaterial)] = int(scene_.materials.size());
  scene_.materials.push_back(m);
  return uint32_t(materialSlots_[size_t(gltfMaterial)]);
}

void MaterialTable::warnIgnoredProperties(const tinygltf::Material& src) const {
  if (src.occlusionTexture.index >= 0)
    ctx_.ignoring("occlusionTexture", "ambient occlusion maps are for rasterizers; a path tracer computes occlusion itself");
}

int MaterialTable::textureFor(const tinygltf::TextureInfo& info, int materialIndex, const char* slot) {
  if (info.index < 0) return -1;
  const std::string where = "material " + std::to_string(materialIndex) + " " + slot;
  if (size_t(info.index) >= textureSlots_.size()) {
    ctx_.fail(where + " refers to texture " + std::to_string(info.index) + ", which does not exist");
  }
  int& slotIndex = textureSlots_[size_t(info.index)];
  if (slotIndex == -1) {
    Texture texture;
    if (convertTexture(info.index, texture)) {
      slotIndex = int(scene_.textures.size());
      scene_.textures.push_back(std::move(texture));
    } else {
      slotIndex = -2;  // unusable; already reported
    }
  }
  return slotIndex >= 0 ? slotIndex : -1;
}

}  // namespace gltf
}  // namespace mixtrace
