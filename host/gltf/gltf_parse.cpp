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

#include "gltf/gltf_internal.h"
#include "gltf/gltf_limits.h"
#include "gltf/json_nesting.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace gltf {

void LoadContext::fail(const std::string& message) const { throw Error(path + ": " + message); }

void LoadContext::warning(const std::string& message) const { warn(path + ": " + message); }

namespace {

// The extensions whose meaning the renderer implements; anything else is ignored when optional
// and refused when required.
const std::set<std::string>& supportedExtensions() {
  static const std::set<std::string> kSupported = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
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

void checkExtensions(const LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model;
  std::vector<std::string> refused;
  for (const std::string& name : model.extensionsRequired) {
    if (!supportedExtensions().count(name)) refused.push_back(name);
  }
  if (!refused.empty()) {
    std::string list;
    for (const std::string& name : refused) list += (list.empty() ? "" : ", ") + name;
    throw Error(ctx.path + " requires unsupported glTF extension" + (refused.size() > 1 ? "s " : " ") + list);
  }
  std::set<std::string> reported;
  for (const std::string& name : model.extensionsUsed) {
    if (supportedExtensions().count(name) || !reported.insert(name).second) continue;
    ctx.warning("uses unsupported glTF extension " + name + "; its data is ignored");
  }
}

}  // namespace

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
  try {
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
      const uint32_t length = validateGlbContainer(ctx, bytes);
      checkJsonNesting(ctx, bytes.data() + 20, readLittleEndian32(&bytes[12]));
      ok = parser.LoadBinaryFromMemory(&ctx.model, &err, &warnings, bytes.data(), length, baseDir);
    } else {
      size_t start = 0;
      if (!looksLikeJson(bytes, start)) ctx.fail("is not a glTF file (neither a JSON object nor binary glTF)");
      checkJsonNesting(ctx, bytes.data() + start, bytes.size() - start);
      ok = parser.LoadASCIIFromString(&ctx.model, &err, &warnings, reinterpret_cast<const char*>(bytes.data() + start),
                                      static_cast<unsigned int>(bytes.size() - start), baseDir);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // tinygltf throws from a few corners (e.g. std::vector::at on an empty BIN chunk).
    ctx.fail("malformed glTF: " + condenseMessage(e.what()));
  }
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
