#version 460
#extension GL_GOOGLE_include_directive : require
// The interface's pair-table rows (shared/cms_pair_state.h) name 64-bit keys.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Stage 4: any-hit test of every queued shadow ray; an unoccluded one adds its contribution.
// Each path queues at most one shadow ray per depth, so the add needs no atomics. With
// controlled mixture sampling the ray's sample also adds its terms of b to its cell: the
// integrand includes visibility, known only here.
#include "wavefront/shadow_interface.h"
#define PASS_BUFFERS SHADOW_BUFFERS
#define PASS_UNREAD_BUFFERS SHADOW_UNREAD_BUFFERS
#define PASS_PAIR_BUFFERS 1
#define PASS_CONSTANTS VertexConstants
#define PASS_READS_SOLUTION_VIEWS
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"
#define EMITTERS_UNIFORM (LIGHT_SELECTION == kLightSelectUniform)
#include "gpu/cms_statistics.glsl"
#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/cms_sampling.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.shadowCount) return;
  ShadowRay s = shadowQueue[i];
  if (CMS_PAIR_TECHNIQUES && (s.flags & kShadowRayBsdfPair) != 0u) {
    settleBsdfPair(s.cell, s.cluster, s.source, s.pk, s.pB, s.ck, s.integrand, s.throughput, s.path, s.contribution.x);
    return;
  }
  // A hidden light point (per-triangle control variate) is settled here untraced.
  // (Records carry flags only under CMS_SELECTION: shade.comp queueShadowRecord.)
  bool hidden = CMS_SELECTION && (s.flags & kShadowRayHidden) != 0u;
  bool visible = !hidden && !traceAny(s.origin, s.direction, s.tMax);
  if (visible) addRadiance(s.path, s.contribution);
  if (CMS_SELECTION && (s.flags & kShadowRayCms) != 0u)
    settleLightSample(s.cell, s.cluster, s.pk, s.ck, visible ? s.pB : 0.0, visible ? s.integrand : vec3(0.0), s.throughput,
                      s.path, s.source);
}
