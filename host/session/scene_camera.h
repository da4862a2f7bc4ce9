#pragma once
// The camera a render (or the viewer) starts from: the file's, or the default framing of the
// bounds when the file has none, with the parts the command line sets (--look-from, --look-at,
// --up, --fov) replacing the corresponding parts of that camera.
#include <string>

#include <glm/glm.hpp>

#include "session/options.h"
#include "scene/scene.h"

namespace mixtrace {

// What given on the command line alone already cannot make a camera (look-from equal to look-at,
// a zero up, up parallel to the view direction). Throws mixtrace::Error naming the options.
void checkCameraOptions(const CameraOptions& camera);

// Replaces the parts of scene.camera that `camera` sets. A part it leaves out comes from the
// file's camera (its position, its up, its field of view, and as the look-at point the point
// straight ahead of it at the distance of the bounds' centre) or, when the file has none, from
// the default framing (outside the bounds, looking at their centre). Throws mixtrace::Error when
// the combination is no camera. Returns the look-at point (for messages).
glm::dvec3 applyCameraOptions(Scene& scene, const CameraOptions& camera);

// Loads the scene (confined to o.assetRoot), applies o.camera and, unless the file's own camera is used unchanged, says
// which camera is used (one info line: position, target, up, field of view).
Scene loadSceneForRendering(const std::string& scenePath, const RenderOptions& o);

// The film's shape from the file camera's aspectRatio (glTF: width / height) where the command line
// leaves it open: with --width alone the height follows, with --height alone the width, with
// neither the default width stays and the height follows; with both (or no aspectRatio) nothing
// changes. Each side stays within [1, kMaxImageSide]. Says so in one info line when it changes a side.
void applyFileAspectRatio(RenderOptions& o, const Scene& scene);

}  // namespace mixtrace
