// Reading a glTF file into a tinygltf::Model. tinygltf does the JSON work; this file adds what it
// does not guarantee: one-line errors, container checks on .glb before tinygltf trusts its chunk
// lengths, a flat nesting scan before tinygltf's recursive parser sees the JSON, confinement of
// external files (gltf_files.cpp), and deferring image decoding until the bytes have been validated.
#include <algorithm>
#include <cstring>
#include <exception>
#include <limits>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gltf/gltf_internal.h"
#include "gltf/gltf_limits.h"
#include "gltf/json_nesting.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace gltf {

void LoadContext::fail(const std::string& message) const { throw Error(path + ": " + message); }

void LoadContext::warning(const std::string& message) const { warn(path + ": " + message); }

void LoadContext::ignoring(const std::string& property, const std::string& why) const {
  if (ignored_.insert(property).second) warning("ignoring " + property + ": " + why);
}

namespace {

// The extensions whose meaning the renderer implements; anything else is ignored when optional
// and refused when required.
const std::set<std::string>& supportedExtensions() {
  static const std::set<std::string> kSupported = {
      "KHR_lights_punctual",        "KHR_materials_emissive_strength", "KHR_materials_ior",
      "KHR_materials_transmission", "KHR_materials_volume",            "KHR_mesh_quantization",
      "KHR_texture_transform"};
  return kSupported;
}

std::vector<std::string> nonEmptyLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const size_t last = line.find_last_not_of(" \t\r");
    lines.push_back(line.substr(first, last - first + 1));
  }
  return lines;
}

std::vector<unsigned char> readSceneFile(const std::string& path) {
  std::vector<unsigned char> bytes;
  const std::string problem = readRegularFile(path, kMaxFileBytes, bytes);
  if (!problem.empty()) throw Error(path + ": " + problem);
  return bytes;
}

uint32_t readLittleEndian32(const unsigned char* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

// Checks the GLB header and chunk table so that tinygltf never reads past the file (its own check
// of the BIN chunk forgets the 8-byte chunk header). Returns the length the header declares.
uint32_t validateGlbContainer(const LoadContext& ctx, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 12) {
    ctx.fail("binary glTF is truncated (" + std::to_string(bytes.size()) + " bytes, its header needs 12)");
  }
  const uint32_t version = readLittleEndian32(&bytes[4]);
  if (version != 2) ctx.fail("unsupported binary glTF version " + std::to_string(version) + " (only 2 is supported)");
  const uint32_t length = readLittleEndian32(&bytes[8]);
  if (length > bytes.size()) {
    ctx.fail("binary glTF is truncated (its header declares " + std::to_string(length) + " bytes, the file has " +
             std::to_string(bytes.size()) + ")");
  }
  if (length < 20) ctx.fail("binary glTF has no JSON chunk");
  uint64_t offset = 12;
  int chunk = 0;
  while (offset < length) {
    if (length - offset < 8) ctx.fail("binary glTF is truncated inside the header of chunk " + std::to_string(chunk));
    const uint32_t chunkLength = readLittleEndian32(&bytes[offset]);
    const uint32_t chunkType = readLittleEndian32(&bytes[offset + 4]);
    if (chunk == 0 && chunkType != 0x4E4F534Au) ctx.fail("binary glTF does not start with a JSON chunk");
    if (uint64_t(chunkLength) > length - offset - 8) {
      ctx.fail("binary glTF is truncated (chunk " + std::to_string(chunk) + " declares " + std::to_string(chunkLength) +
               " bytes, " + std::to_string(length - offset - 8) + " remain)");
    }
    offset += 8 + uint64_t(chunkLength);
    ++chunk;
  }
  return length;
}

// Image callback: keep the encoded bytes instead of decoding. For images stored in a bufferView
// tinygltf hands us a pointer it has not range-checked, so those are not touched here at all;
// decodeImage reads them after validating the view.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

bool looksLikeJson(const std::vector<unsigned char>& bytes, size_t& start) {
  start = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) start = 3;  // UTF-8 BOM
  size_t i = start;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n')) ++i;
  return i < bytes.size() && bytes[i] == '{';
}

// extensionsRequired straight from the JSON text, for a file tinygltf could not parse: empty when
// the text is not JSON or the list is absent or malformed (the parser's own error then stands).
std::vector<std::string> requiredExtensionsOf(const unsigned char* json, size_t size) {
  std::vector<std::string> names;
  const nlohmann::json doc = nlohmann::json::parse(json, json + size, nullptr, false);
  if (!doc.is_object()) return names;
  const auto it = doc.find("extensionsRequired");
  if (it == doc.end() || !it->is_array()) return names;
  for (const nlohmann::json& name : *it)
    if (name.is_string()) names.push_back(name.get<std::string>());
  return names;
}

void checkExtensions(const LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model;
  const std::string refused = unsupportedRequiredExtensions(model.extensionsRequired);
  if (!refused.empty()) throw Error(ctx.path + " " + refused);
  std::set<std::string> reported;
  for (const std::string& name : model.extensionsUsed) {
    if (supportedExtensions().count(name) || !reported.insert(name).second) continue;
    ctx.warning("uses unsupported glTF extension " + name + "; its data is ignored");
  }
}

}  // namespace

std::string unsupportedRequiredExtensions(const std::vector<std::string>& required) {
  std::string list;
  size_t count = 0;
  for (const std::string& name : required) {
    if (supportedExtensions().count(name)) continue;
    list += (list.empty() ? "" : ", ") + name;
    ++count;
  }
  if (count == 0) return "";
  return std::string("requires unsupported glTF extension") + (count > 1 ? "s " : " ") + list;
}

// tinygltf's messages are often several lines, and quote whole data URIs (megabytes of base64);
// the user gets one short line.
std::string condenseMessage(const std::string& text) {
  std::string joined;
  for (std::string line : nonEmptyLines(text)) {
    for (size_t at = line.find("data:"); at != std::string::npos; at = line.find("data:", at + 1)) {
      const size_t comma = line.find(',', at);
      const size_t end = std::min(line.find_first_of(" '\"", at), line.size());
      if (comma < end) line.replace(comma + 1, end - comma - 1, "...");
    }
    if (!joined.empty()) joined += "; ";
    joined += line;
  }
  return joined.empty() ? std::string("unknown error") : joined;
}

// The JSON parser and tinygltf's conversion of extras/extensions recurse once per level, so a
// small file of a few thousand [ or { overflows the stack; the scan (json_nesting.h) is flat.
void checkJsonNesting(const LoadContext& ctx, const unsigned char* json, size_t size) {
  const size_t at = jsonNestingExceededAt(reinterpret_cast<const char*>(json), size, kMaxJsonNesting);
  if (at != kJsonNestingOk)
    ctx.fail("JSON nests deeper than " + std::to_string(kMaxJsonNesting) + " levels (at byte " + std::to_string(at) +
             "); refused before parsing");
}

void parseGltfFile(LoadContext& ctx) {
  const std::vector<unsigned char> bytes = readSceneFile(ctx.path);
  if (bytes.empty()) ctx.fail("file is empty, not a glTF file");
  static_assert(kMaxFileBytes <= std::numeric_limits<unsigned int>::max(), "tinygltf takes unsigned int sizes");
  AssetFiles files(ctx.path, ctx.assetRoot);

  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&keepEncodedImage, nullptr);
  parser.SetFsCallbacks(files.callbacks());
  const std::string& baseDir = files.baseDir();
  std::string err;
  std::string warnings;
  bool ok = false;
  const unsigned char* json = nullptr;   // the JSON text, once the container checks passed
  size_t jsonSize = 0;
  // Where the parser fails, a file that requires an extension we cannot honour is refused for that
  // (its Draco or meshopt data, or the files holding it, are what the parser could not read).
  auto refuseUnsupportedRequired = [&]() {
    if (!json) return;
    const std::string refused = unsupportedRequiredExtensions(requiredExtensionsOf(json, jsonSize));
    if (!refused.empty()) throw Error(ctx.path + " " + refused);
  };
  try {
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
      const uint32_t length = validateGlbContainer(ctx, bytes);
      json = bytes.data() + 20;
      jsonSize = readLittleEndian32(&bytes[12]);
      checkJsonNesting(ctx, json, jsonSize);
      ok = parser.LoadBinaryFromMemory(&ctx.model, &err, &warnings, bytes.data(), length, baseDir);
    } else {
      size_t start = 0;
      if (!looksLikeJson(bytes, start)) ctx.fail("is not a glTF file (neither a JSON object nor binary glTF)");
      json = bytes.data() + start;
      jsonSize = bytes.size() - start;
      checkJsonNesting(ctx, json, jsonSize);
      ok = parser.LoadASCIIFromString(&ctx.model, &err, &warnings, reinterpret_cast<const char*>(json),
                                      static_cast<unsigned int>(jsonSize), baseDir);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // tinygltf throws from a few corners (e.g. std::vector::at on an empty BIN chunk).
    refuseUnsupportedRequired();
    ctx.fail("malformed glTF: " + condenseMessage(e.what()));
  }
  if (!ok) refuseUnsupportedRequired();
  // A refused external file is fatal even where tinygltf only warns (images): the file asked for
  // something it must not have, and its own message would name the path it built.
  if (!files.firstRefusal().empty()) ctx.fail(files.firstRefusal());
  warnings = files.hidePaths(warnings);
  err = files.hidePaths(err);
  for (const std::string& line : nonEmptyLines(warnings)) ctx.warning(line);
  if (!ok) ctx.fail("malformed glTF: " + condenseMessage(err));
  for (const std::string& line : nonEmptyLines(err)) ctx.warning(line);  // reported but not fatal to tinygltf
  checkExtensions(ctx);
}

}  // namespace gltf
}  // namespace mixtrace
