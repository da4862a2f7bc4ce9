#pragma once
// What a method needs of controlled mixture sampling (../shared/cms.md), and the light clusters
// it samples through. The pt-* methods use none of it.
#include <string>
#include <vector>

#include "scene/light_clusters.h"
#include "scene/prepared_scene.h"
#include "shared/layouts.h"

namespace mixtrace {

struct CmsMethod {
  bool clusters = false;        // lights chosen through per-cell cluster selection (learned, cv, cms)
  bool controlVariate = false;  // cv, cms
  bool learnSelection = false;  // learned, cms
  LightSelection defaults = LightSelection::Power;  // the default (and defensive) selection
};

CmsMethod cmsMethodFor(const std::string& method);

struct CmsScene {
  LightClusters clusters;
  std::vector<shared::ClusterLightGpu> clusterLights;  // clusters' lights with in-cluster CDFs
};

// Clusters the scene's lights and records in each LightGpu its cluster and in-cluster pmf.
CmsScene setUpClusters(PreparedScene& scene, uint32_t maxClusters, LightSelection defaults);

}  // namespace mixtrace
