#pragma once
// What a renderer for one method needs, from the command line's options: the scene prepared with
// the method's light selection, the render settings and, for the learning methods, the light
// clusters. Shared by `render` and `view` (which sets up one per method it shows).
#include <string>

#include "session/options.h"
#include "cms/cms_setup.h"
#include "render/renderer.h"
#include "scene/prepared_scene.h"

namespace mixtrace {

struct MethodSetup {
  PreparedScene prepared;
  RenderSettings settings;
  CmsScene cms;                // clusters when settings.cms.clusters
  std::string estimator;       // what runs: the method, or pt-power where cms reduces to it
  const CmsScene* clusters() const { return settings.cms.clusters ? &cms : nullptr; }
};

// `method` overrides o.method (the viewer switches methods). Says so (info line) when cms reduces
// to plain MIS on a scene with one light cluster.
MethodSetup setUpMethod(const Scene& scene, const RenderOptions& o, const std::string& method);

}  // namespace mixtrace
