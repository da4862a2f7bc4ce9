// Light clusters of controlled mixture sampling (docs/estimator.md §2): one sampling technique per
// cluster. A cluster's lights are listed contiguously in a separate array (clusterLights, of
// ClusterLightGpu in layouts.h), so a cluster record is four words. Built on the host by
// host/cms/light_clusters.cpp; its layout is checked with those of layouts.h
// (host/vulkan/layout_checks.cpp).
#ifndef MIXTRACE_SHARED_CLUSTER_LAYOUT_H
#define MIXTRACE_SHARED_CLUSTER_LAYOUT_H
#include "shared/dialect.h"
SHARED_BEGIN

// ClusterGpu.kind. A cluster never mixes the two: delta (punctual) techniques are densities in
// counting measure, area techniques in solid angle / area measure.
const uint kClusterArea = 0u;
const uint kClusterDelta = 1u;

struct ClusterGpu {
  uint firstLight;     // into clusterLights[]
  uint lightCount;
  uint kind;           // kClusterArea or kClusterDelta
  float power;         // summed emitted power of its lights (luminance, W), as LightSet::power
};
const uint kTexelsPerCluster = 1u;

SHARED_END
#endif
