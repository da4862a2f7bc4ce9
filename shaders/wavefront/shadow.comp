#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 4: any-hit test of every queued shadow ray; an unoccluded one adds its contribution.
// Each path queues at most one shadow ray per depth, so the add needs no atomics. With
// controlled mixture sampling the ray's sample also adds its terms of b to its cell: the
// integrand includes visibility, known only here.
#include "gpu/buffers.glsl"
#include "gpu/cms_buffers.glsl"
#include "gpu/cms_statistics.glsl"
#include "shared/bvh_traverse.h"
#include "shared/cms_sampling.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.shadowCount) return;
  ShadowRay s = shadowQueue[i];
  bool visible = (s.flags & kShadowRayHidden) == 0u && !traceAny(s.origin, s.direction, s.tMax);
  if (visible) radiance[s.path] += s.contribution;
  if (!CMS_SELECTION || (s.flags & kShadowRayCms) == 0u) return;
  // A hidden light point cannot be reached by the BSDF: there p_B = 0 and p_eff = c_k p_k.
  uint L = pc.clusterCount;
  float pB = visible ? s.pB : 0.0;
  float peff = s.ck * s.pk + pB;
  if (!(peff > 0.0)) return;
  if (CMS_CONTROL_VARIATE && cellSolutionValid(s.cell, L))
    radiance[s.path] -= s.throughput * (cellAlpha(s.cell, L, s.cluster) * s.pk + cellAlphaB(s.cell, L) * pB) / peff;
  float w = sampleWeight(s.throughput, s.path);
  addSampleToA(s.cell, s.cluster, s.pk, pB, peff, w);
  if (visible) addSampleToB(s.cell, s.cluster, s.integrand, w * s.pk / (peff * peff), w * pB / (peff * peff));
}
