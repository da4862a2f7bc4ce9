#pragma once
// The environment light a render (or the viewer) gets from its options: --env FILE (an
// equirectangular map: .exr, .hdr or .pfm), --env-color R,G,B (uniform), --env none (black), each
// scaled by --env-scale and turned by --env-rotate about +Y. Without any of them a scene without
// lights gets a uniform white environment of radiance 1 and one line that says so, as glTF viewers
// light a downloaded model; a scene with lights gets none.
#include <string>

#include "scene/scene.h"
#include "session/options.h"

namespace mixtrace {

// The largest map kept as it is (texels): larger ones are halved (2x2 box filter) until they fit
// one storage buffer of lavapipe's 128 MiB with their distribution (shared/environment_layout.h).
constexpr size_t kMaxEnvironmentTexels = size_t(4096) * 1536;

// Reads an environment image: linear RGB, top row first, every value finite; negative values
// become 0 (with a warning). Throws Error with one line naming the file and the problem.
Environment readEnvironmentImage(const std::string& path);

// Sets scene.environment from the options (above). Throws Error for contradictory options or an
// unreadable map.
void applyEnvironmentOptions(Scene& scene, const RenderOptions& o);

// Whether the loaded scene has a light of its own (an emissive material on a triangle, or a
// punctual light), before the light set is built.
bool sceneHasLights(const Scene& scene);

}  // namespace mixtrace
