#pragma once
// What a renderer for one method needs besides the prepared scene, from the command line's
// options: the render settings and the method's light tables (its light selection and, for the
// learning methods, the light clusters). Shared by `render` and `view`: both prepare the scene
// once, and the viewer sets up one method after another on it.
#include <string>

#include "session/options.h"
#include "cms/method_lights.h"
#include "backend/renderer.h"
#include "scene/prepared_scene.h"

namespace mixtrace {

struct MethodSetup {
  RenderSettings settings;
  MethodLights lights;         // the selection table; the clusters when the method has them
  std::string estimator;       // what runs: the method, or pt-power where cms reduces to it
  bool cellsChosen = false;    // settings.cells came from --cells auto (cms/grid_resolution.h)
};

// `method` overrides o.method (the viewer switches methods). Says so (info line) when cms reduces
// to plain MIS on a scene with one light cluster. Resolves --cells auto for the methods with cells
// (both backends then key vertices to the same grid). The scene is only read: every method shares it.
MethodSetup setUpMethod(const PreparedScene& prepared, const RenderOptions& o, const std::string& method);

}  // namespace mixtrace
