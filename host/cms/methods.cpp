#include "cms/methods.h"

namespace mixtrace {

const std::vector<MethodInfo>& methodTable() {
  // cv is the published method: the control variate with the selection kept fixed. It keeps
  // uniform selection: uniform over emissive triangles (each cluster weighted by its triangle count,
  // scene/light_selection.h), as the paper's baseline and pbrt-v4's uniform light sampler.
  static const std::vector<MethodInfo> table = {
      // name, summary, selection, clusters, learnSelection, controlVariate, viewerKey
      {"pt-uniform", "MIS path tracer, every emissive triangle equally likely", LightSelection::Uniform, false, false, false, '1'},
      {"pt-power", "MIS path tracer, light picked by power", LightSelection::Power, false, false, false, '2'},
      {"learned", "per-cell learned cluster selection, no control variate", LightSelection::Bvh, true, true,
       false, '3'},
      {"cv", "control variate per cell, selection kept fixed", LightSelection::Uniform, true, false, true, '4'},
      {"cms", "control variate and learned selection (Hua et al. 2023)", LightSelection::Bvh, true, true, true,
       '5'},
      {"pt-bvh", "MIS path tracer, light picked by a light BVH", LightSelection::Bvh, false, false, false, '6'},
  };
  return table;
}

const MethodInfo* findMethod(const std::string& name) {
  for (const MethodInfo& m : methodTable())
    if (name == m.name) return &m;
  return nullptr;
}

const MethodInfo* plainMisMethodFor(LightSelection selection) {
  for (const MethodInfo& m : methodTable())
    if (m.selection == selection && !m.clusters && !m.learnSelection && !m.controlVariate) return &m;
  return nullptr;
}

const MethodInfo* methodForViewerKey(char key) {
  for (const MethodInfo& m : methodTable())
    if (key == m.viewerKey) return &m;
  return nullptr;
}

std::string viewerKeyRange() {
  return std::string(1, methodTable().front().viewerKey) + "-" + std::string(1, methodTable().back().viewerKey);
}

}  // namespace mixtrace
