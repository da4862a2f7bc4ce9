#pragma once
// What a method needs of controlled mixture sampling (docs/estimator.md), and the light clusters
// it samples through. The pt-* methods use none of it.
#include <string>
#include <vector>

#include "cms/methods.h"
#include "cms/light_clusters.h"
#include "cms/light_techniques.h"
#include "scene/prepared_scene.h"
#include "shared/layouts.h"

namespace mixtrace {

struct CmsMethod {
  bool clusters = false;        // lights chosen through per-cell cluster selection (learned, cv, cms)
  bool controlVariate = false;  // cv, cms
  bool learnSelection = false;  // learned, cms
  LightSelection defaults = LightSelection::Power;  // the default (and defensive) selection
};

// The flags of the method's row (cms/methods.h); none for a pt-* method or a name that is no method.
CmsMethod cmsMethodFor(const MethodInfo& method);
CmsMethod cmsMethodFor(const std::string& method);

struct CmsScene {
  LightClusters clusters;
  std::vector<shared::ClusterLightGpu> clusterLights;  // clusters' lights with in-cluster CDFs
  LightTechniques techniques;   // the control variate's techniques (per triangle, cms/light_techniques.h)
};

// Clusters the scene's lights and records in the method's selection table (one entry per light,
// scene/light_selection.h) each light's cluster and in-cluster pmf, and builds the control
// variate's techniques within maxTechniques. The scene stays as it is.
CmsScene setUpClusters(const PreparedScene& scene, std::vector<shared::LightSelectionGpu>& selection,
                       uint32_t maxClusters, LightSelection defaults,
                       uint32_t maxTechniques = kDefaultMaxTechniques);

// Whether the method cms, on a scene with these clusters, is better run as plain MIS (pt-power's
// estimator): with at most one cluster there is no selection to learn, and the control variate
// alone measured no gain there, while it costs about 1.3x per sample on lavapipe (docs/estimator.md
// §7 note in benchmarks/README.md: relMSE at 64 spp, 160x120, cms vs pt-power: Cornell box 1.00x,
// Veach MIS lit by only one of its lights 1.00x and 0.99x). The research methods learned and cv run
// as asked.
bool cmsReducesToPlainMis(const CmsMethod& method, const CmsScene& scene);

// The line that says why cms runs as plain MIS on this scene (cmsReducesToPlainMis): that its
// lights form one cluster, or that it has none at all; `estimator` names what it runs instead.
std::string plainMisNote(const CmsScene& scene, const std::string& estimator);

}  // namespace mixtrace
