#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 4: any-hit test of every queued shadow ray; an unoccluded one adds its contribution.
// Each path queues at most one shadow ray per depth, so the add needs no atomics. With
// controlled mixture sampling the ray's sample also adds its terms of b to its cell: the
// integrand includes visibility, known only here.
#include "gpu/buffers.glsl"
#include "gpu/cms_buffers.glsl"
#include "shared/bvh_traverse.h"
#include "shared/cms_cells.h"
#include "shared/cms_layouts.h"

layout(local_size_x = kWorkgroupSize) in;

void addStat(uint cell, uint index, float value) {
  if (value != 0.0) atomicAdd(cellStats[cell * cellStatsStride(pc.clusterCount) + index], value);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.shadowCount) return;
  ShadowRay s = shadowQueue[i];
  if (traceAny(s.origin, s.direction, s.tMax)) return;
  radiance[s.path] += s.contribution;
  if (CMS_SELECTION && s.cell != kNoCell) {
    uint L = pc.clusterCount;
    for (uint c = 0u; c < 3u; ++c) {
      addStat(s.cell, statsBk(L, s.cluster, c), s.integrand[c] * s.statsK);
      addStat(s.cell, statsBB(L, c), s.integrand[c] * s.statsB);
    }
  }
}
