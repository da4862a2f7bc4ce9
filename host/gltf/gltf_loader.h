#pragma once
// glTF 2.0 (.gltf or .glb) in, the renderer's flattened world-space Scene out.
#include <string>

#include "scene/scene.h"

namespace mixtrace {

struct GltfLoadOptions {
  // External buffers and images must lie under this folder; empty: the scene's own folder.
  // For trusted files that share assets with siblings (render --asset-root DIR).
  std::string assetRoot;
};

// Loads the default scene (or scene 0) of a glTF 2.0 file. Binary vs JSON is decided by the file's
// magic bytes, not its extension. Everything the user can get wrong (missing or malformed file,
// out-of-range data, unsupported required extensions, no triangles) throws mixtrace::Error with
// one line naming the file; recoverable oddities are reported through mixtrace::warn. Hostile
// files are bounded by gltf/gltf_limits.h and confined to the asset root.
Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});

}  // namespace mixtrace
