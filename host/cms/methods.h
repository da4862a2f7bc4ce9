#pragma once
// The methods, in one table: every place that needs to know them (the option parser and --help,
// method set-up, CMS set-up, the viewer's keys) reads this row, so a new estimator is one row here.
// Device-free, and in cms/ so that cms set-up can read the flags without an upward include.
#include <string>
#include <vector>

#include "scene/light_selection.h"

namespace mixtrace {

struct MethodInfo {
  const char* name;        // what --method takes
  const char* summary;     // its line in --help
  LightSelection selection;  // how the method picks lights (the clusters' defaults too)
  bool clusters;           // lights chosen through per-cell cluster selection (docs/estimator.md)
  bool learnSelection;     // the per-cell cluster selection is learned
  bool controlVariate;     // the per-cell control variate is used
  char viewerKey;          // the viewer's key for it (shift+key: the split view's right side)
};

// The rows, in --help order; viewer keys run '1'..'N' in this order.
const std::vector<MethodInfo>& methodTable();

// The row of a method, or nullptr where the name is not a method.
const MethodInfo* findMethod(const std::string& name);

// The row of a viewer key, or nullptr where the key selects no method.
const MethodInfo* methodForViewerKey(char key);

// The viewer's method keys as the help and the viewer's banner name them: "first-last" ("1-5").
std::string viewerKeyRange();

// The method a render uses when --method is not given.
inline constexpr const char* kDefaultMethod = "cms";

// Plain MIS with power-proportional light selection: the viewer's split-view partner for the
// learning methods.
inline constexpr const char* kPlainMisMethod = "pt-power";

// The plain-MIS row (no clusters, no learning, no control variate) that picks lights by
// `selection`: what a learning method reduces to where there is nothing to learn (cms on a scene
// of one light cluster runs its own default selection, the light BVH, as pt-bvh). nullptr where no
// row does.
const MethodInfo* plainMisMethodFor(LightSelection selection);

}  // namespace mixtrace
