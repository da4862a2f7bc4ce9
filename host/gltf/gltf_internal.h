#pragma once
// Pieces of the glTF loader shared between its source files (not a public interface).
//
// Debian ships tinygltf as a shared library (libtinygltf.so, which also carries stb_image and the
// JSON parser), so the header is included WITHOUT TINYGLTF_IMPLEMENTATION: we only need the
// declarations of Model, TinyGLTF and tinygltf::LoadImageData.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/scene.h"
#include "shared/constants.h"

namespace mixtrace {
namespace gltf {

// What every stage needs: the parsed model and the file name for messages.
struct LoadContext {
  std::string path;
  std::string assetRoot;  // GltfLoadOptions::assetRoot
  tinygltf::Model model;

  // Throws mixtrace::Error("<path>: <message>").
  [[noreturn]] void fail(const std::string& message) const;
  // mixtrace::warn("<path>: <message>").
  void warning(const std::string& message) const;
  // Names a property the file uses and the renderer does not honour, once per property and file:
  // "<path>: ignoring <property>: <why>" (issue 14: say what is ignored, never drop it in silence).
  void ignoring(const std::string& property, const std::string& why) const;

 private:
  mutable std::set<std::string> ignored_;
};

// --- gltf_files.cpp: what the loader may read, and how.
// Reads `path` if it is a regular file of at most `maxBytes` (never blocks on a FIFO); returns ""
// on success, else why not ("is a FIFO, not a regular file"), for the caller to prefix a name to.
std::string readRegularFile(const std::string& path, uint64_t maxBytes, std::vector<unsigned char>& out);

// The file-system callbacks tinygltf uses for external buffers and images: URIs resolve against
// the scene's folder only (no current-directory fallback, no absolute paths), must stay under
// the asset root after resolving "..", and symbolic links (default: the scene's folder), and
// must name regular files within kMaxFileBytes.
class AssetFiles {
 public:
  // `assetRoot` empty: the scene's folder. Throws when the folder or the root cannot be resolved.
  AssetFiles(const std::string& scenePath, const std::string& assetRoot);
  AssetFiles(const AssetFiles&) = delete;
  AssetFiles& operator=(const AssetFiles&) = delete;

  // Callbacks pointing at this object, which must outlive their use.
  tinygltf::FsCallbacks callbacks();
  // The base directory to hand tinygltf (absolute, so its "./" fallback is recognisable).
  const std::string& baseDir() const { return baseDir_; }
  // The first URI refused (outside the root, not a regular file, too large), one line; "" if none.
  const std::string& firstRefusal() const { return firstRefusal_; }
  // tinygltf quotes the paths it built; the user wrote URIs relative to the scene.
  std::string hidePaths(std::string text) const;

 private:
  bool resolve(const std::string& joined, std::filesystem::path& resolved);
  bool exists(const std::string& joined);
  bool read(std::vector<unsigned char>& out, std::string& err, const std::string& joined);
  void refuse(const std::string& message);
  bool rootIsSceneDir() const;

  std::string baseDir_;  // canonical scene folder
  std::string prefix_;   // baseDir_ with a trailing '/'
  std::filesystem::path root_;
  std::string firstRefusal_;
};

// --- gltf_parse.cpp: file -> tinygltf::Model, with the container checks tinygltf skips.
// Throws for a missing, malformed, truncated, too large or too deeply nested file (or one that is
// not a regular file), for refused external files and for unsupported required extensions.
// Images are NOT decoded here: their encoded bytes are kept (Image::as_is) and decoded on demand
// by decodeImage once the data they live in has been validated.
void parseGltfFile(LoadContext& ctx);
// "requires unsupported glTF extension(s) X, Y" for the extensions of `required` (a file's
// extensionsRequired) the renderer cannot honour; "" when there are none. parseGltfFile also reads
// the list from the JSON text where the parser fails first, so that a Draco or meshopt file is
// refused for what it is, not for the data tinygltf cannot read.
std::string unsupportedRequiredExtensions(const std::vector<std::string>& required);
// Throws when [ and { nest deeper than kMaxJsonNesting in `json` (strings skipped).
void checkJsonNesting(const LoadContext& ctx, const unsigned char* json, size_t size);
// Joins the non-empty lines of a (tinygltf) message with "; " so errors stay one line.
std::string condenseMessage(const std::string& text);

// --- gltf_float_range.cpp: doubles from the file that must become floats.
bool fitsInFloat(double value);
// float(value); throws "<property> 1e+39 does not fit in a float" for finite values beyond
// float's range (non-finite ones are left to the caller, which has its own fallbacks).
float checkedFloat(const LoadContext& ctx, double value, const std::string& property);
// checkedFloat on each element, named property[i].
void checkFitsInFloat(const LoadContext& ctx, const std::vector<double>& values, const std::string& property);

// --- gltf_accessors.cpp: bounds-checked reading of accessor data.
int componentSizeOf(int componentType);   // 0 for an unknown type
int componentCountOf(int accessorType);   // 0 for an unknown type

// A validated accessor: constructing it checks that every element lies inside its bufferView and
// buffer, so the reads below never leave the data.
class AccessorReader {
 public:
  // `role` names the accessor in messages ("POSITION of mesh 2 primitive 0").
  AccessorReader(const LoadContext& ctx, int accessorIndex, const std::string& role);

  size_t count() const { return count_; }
  int componentType() const { return componentType_; }
  int type() const { return type_; }
  bool normalized() const { return normalized_; }
  int index() const { return index_; }

  // Component c of element i as float; normalised integers map to [0,1] / [-1,1] per the spec.
  float component(size_t i, int c) const;
  // Component 0 of element i as an unsigned integer (index buffers).
  uint32_t unsignedValue(size_t i) const;
  glm::vec2 vec2(size_t i) const { return {component(i, 0), component(i, 1)}; }
  glm::vec3 vec3(size_t i) const { return {component(i, 0), component(i, 1), component(i, 2)}; }

 private:
  const unsigned char* element(size_t i) const { return data_ + i * stride_; }
  void applySparse(const LoadContext& ctx, const tinygltf::Accessor& accessor, const std::string& name,
                   size_t elementSize);

  const unsigned char* data_ = nullptr;  // null: the accessor has no bufferView, all zeros
  std::shared_ptr<const std::vector<unsigned char>> dense_;   // a sparse accessor's elements (data_ points in)
  size_t stride_ = 0;
  size_t count_ = 0;
  int componentType_ = 0;
  int componentSize_ = 0;
  int type_ = 0;
  bool normalized_ = false;
  int index_ = -1;
};

// Returns the bytes of bufferView `viewIndex` after checking it lies inside its buffer.
const unsigned char* bufferViewBytes(const LoadContext& ctx, int viewIndex, size_t& byteLength,
                                     const std::string& role);

// --- gltf_geometry.cpp: one mesh primitive instance -> world-space triangles.
struct GeometryStats {
  size_t degenerate = 0;      // dropped: zero area or non-finite positions
  size_t invalidNormals = 0;  // file normals that were zero or non-finite, replaced
  size_t leftoverIndices = 0; // index/vertex counts not a multiple of 3
};

// Whether a primitive mode has a surface: TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN (not points or lines).
bool isSurfaceMode(int mode);

// Appends the triangles of primitive `primitiveIndex` of mesh `meshIndex` (a surface mode; strips
// and fans are unrolled in the specification's winding), placed by `world`, to `out`; returns how
// many were appended. Winding is reversed under mirroring transforms so the
// front face stays counter-clockwise.
// Which texture coordinates a material's textures read, and how they are transformed
// (KHR_texture_transform: uv' = offset + R(rotation) (scale * uv), R turning the UVs
// counter-clockwise, u' = cos u + sin v, v' = -sin u + cos v, as the extension's examples read).
// The triangles carry one set of UVs, so the mapping is applied to them at load time: exact
// where a material's textures agree (exporters write one transform per material), else the base
// colour texture's serves all, with a warning.
struct UvMapping {
  int set = 0;                                  // TEXCOORD_<set>
  glm::dvec2 offset{0.0};
  double rotation = 0.0;
  glm::dvec2 scale{1.0};
  bool identity() const { return offset == glm::dvec2(0.0) && rotation == 0.0 && scale == glm::dvec2(1.0); }
  glm::vec2 apply(glm::vec2 uv) const;
  bool operator==(const UvMapping& o) const {
    return set == o.set && offset == o.offset && rotation == o.rotation && scale == o.scale;
  }
};

// The texture coordinates a material's textures read: at most two mappings (set and transform),
// baked into each triangle's uv and uv2; secondSlots (kMaterialSecondUv* bits) names the textures
// that read the second.
struct MaterialUvs {
  UvMapping first;
  std::optional<UvMapping> second;
  uint32_t secondSlots = 0;
};

size_t appendPrimitive(const LoadContext& ctx, int meshIndex, int primitiveIndex, const glm::dmat4& world,
                       uint32_t material, const MaterialUvs& uvs, bool needsTangents, uint32_t primitiveId,
                       std::vector<Triangle>& out, GeometryStats& stats);

// --- gltf_materials.cpp: glTF materials and textures -> MaterialGpu and Texture, on demand.
class MaterialTable {
 public:
  MaterialTable(const LoadContext& ctx, Scene& scene);
  // Index into scene.materials for glTF material `gltfMaterial` (-1: the spec's default
  // material); converts it (and its textures) the first time it is asked for.
  uint32_t materialFor(int gltfMaterial);
  // The texture coordinates glTF material `gltfMaterial` reads (set 0, untransformed, for the
  // default material and for a material without textures).
  MaterialUvs uvMappingFor(int gltfMaterial);
  // Whether the material has a normal map (its triangles then need tangents).
  bool hasNormalMap(int gltfMaterial) const;

 private:
  int textureFor(const tinygltf::TextureInfo& info, int materialIndex, const char* slot);
  // Names each material property the renderer does not honour (LoadContext::ignoring).
  void warnIgnoredProperties(const tinygltf::Material& src) const;
  // False (after a warning) when the texture has no image this loader can read.
  bool convertTexture(int textureIndex, Texture& out);

  const LoadContext& ctx_;
  Scene& scene_;
  std::vector<int> materialSlots_;  // glTF material -> scene material, -1 until converted
  int defaultMaterial_ = -1;
  std::vector<int> textureSlots_;   // glTF texture -> scene texture; -1 not yet, -2 unusable
  std::vector<std::optional<MaterialUvs>> uvMappings_;   // per glTF material, once asked for
};

// --- gltf_glass.cpp
// A material's extension object `name`, or null.
const tinygltf::Value* materialExtension(const tinygltf::Material& material, const char* name);
// KHR_materials_transmission's transmissionTexture as a texture reference (index -1: none).
tinygltf::TextureInfo transmissionTextureInfo(const tinygltf::Material& material);
struct GlassParameters {
  float ior = shared::kDefaultIor;   // KHR_materials_ior
  float transmission = 0.0f;         // KHR_materials_transmission's factor
  bool volumetric = false;           // KHR_materials_volume thicknessFactor > 0; thin-walled otherwise
};
// The material's glass extensions, with a warning for each value that is not usable.
GlassParameters readGlass(const LoadContext& ctx, const tinygltf::Material& material, int materialIndex);

// --- gltf_textures.cpp
// Decodes image `imageIndex` (PNG/JPEG/... through tinygltf's stb_image) into texture's size and
// RGBA8 texels, and computes its averageLinear.
void decodeImage(const LoadContext& ctx, int imageIndex, Texture& texture);

}  // namespace gltf
}  // namespace mixtrace
