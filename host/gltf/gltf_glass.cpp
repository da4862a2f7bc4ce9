// KHR_materials_ior, KHR_materials_transmission and KHR_materials_volume: the glass part of a
// material (shaders/shared/dielectric.h). The volume's thickness only decides the geometry (a
// surface that bounds a volume, or a thin wall, as the extension prescribes); its value and
// texture are a rasterizer's stand-in for the geometry a path tracer has.
#include <cmath>

#include "gltf/gltf_internal.h"

namespace mixtrace {
namespace gltf {

const tinygltf::Value* materialExtension(const tinygltf::Material& material, const char* name) {
  const auto it = material.extensions.find(name);
  return it != material.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

tinygltf::TextureInfo transmissionTextureInfo(const tinygltf::Material& material) {
  tinygltf::TextureInfo info;   // index -1: none
  const tinygltf::Value* ext = materialExtension(material, "KHR_materials_transmission");
  if (!ext) return info;
  const tinygltf::Value& t = ext->Get("transmissionTexture");
  if (!t.IsObject()) return info;
  const tinygltf::Value& index = t.Get("index");
  if (index.IsInt() && index.GetNumberAsInt() >= 0) info.index = index.GetNumberAsInt();
  const tinygltf::Value& texCoord = t.Get("texCoord");
  if (texCoord.IsInt() && texCoord.GetNumberAsInt() >= 0) info.texCoord = texCoord.GetNumberAsInt();
  const tinygltf::Value& extensions = t.Get("extensions");
  if (extensions.IsObject())
    for (const std::string& key : extensions.Keys()) info.extensions[key] = extensions.Get(key);
  return info;
}

GlassParameters readGlass(const LoadContext& ctx, const tinygltf::Material& material, int materialIndex) {
  GlassParameters g;
  const std::string where = "material " + std::to_string(materialIndex);
  auto numberOr = [&](const tinygltf::Value* ext, const char* key, double fallback, const char* extension) {
    if (!ext) return fallback;
    const tinygltf::Value& v = ext->Get(key);
    if (!v.IsNumber()) return fallback;
    const double x = v.GetNumberAsDouble();
    if (std::isfinite(x)) return x;
    ctx.warning(where + " has a non-finite " + extension + " " + key + "; using " + std::to_string(fallback));
    return fallback;
  };

  const tinygltf::Value* ior = materialExtension(material, "KHR_materials_ior");
  const double iorValue = numberOr(ior, "ior", double(shared::kDefaultIor), "KHR_materials_ior");
  if (iorValue >= 1.0 && iorValue <= 10.0) {
    g.ior = float(iorValue);
  } else {
    ctx.warning(where + " has KHR_materials_ior " + std::to_string(iorValue) + ", outside [1, 10]; using 1.5");
  }

  const tinygltf::Value* transmission = materialExtension(material, "KHR_materials_transmission");
  const double factor = numberOr(transmission, "transmissionFactor", 0.0, "KHR_materials_transmission");
  g.transmission = float(std::min(std::max(factor, 0.0), 1.0));
  if (g.transmission != factor) ctx.warning(where + " has a transmissionFactor outside [0, 1]; clamped");

  const tinygltf::Value* volume = materialExtension(material, "KHR_materials_volume");
  g.volumetric = numberOr(volume, "thicknessFactor", 0.0, "KHR_materials_volume") > 0.0;
  if (volume) {
    const tinygltf::Value& distance = volume->Get("attenuationDistance");
    const tinygltf::Value& color = volume->Get("attenuationColor");
    if (distance.IsNumber() || color.IsArray())
      ctx.ignoring("KHR_materials_volume attenuation", "glass volumes are clear (no absorption inside)");
  }
  if (g.volumetric && g.transmission > 0.0f && g.ior < shared::kMinVolumeIor) {
    ctx.warning(where + " is volumetric glass of IOR " + std::to_string(g.ior) + "; using " +
                std::to_string(shared::kMinVolumeIor) + " (at 1 refraction has no density)");
    g.ior = shared::kMinVolumeIor;
  }
  return g;
}

}  // namespace gltf
}  // namespace mixtrace
