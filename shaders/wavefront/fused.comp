#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The fused schedule (fused_interface.h): each invocation draws its pixel's camera ray as
// generate.comp does and traces the whole path (shared/path_tracer.h, the CPU backend's loop),
// then leaves its radiance for accumulate.comp. For the methods without learning.
#include "wavefront/fused_interface.h"
#define PASS_BUFFERS FUSED_BUFFERS
#define PASS_CONSTANTS FusedConstants
#include "gpu/buffers.glsl"
#define LIGHT_BVH(i) LIGHT_BVH_FROM_TEXELS(i)
#define LIGHT_SELECT_BVH (LIGHT_SELECTION == kLightSelectBvh)
#define EMITTERS_UNIFORM (LIGHT_SELECTION == kLightSelectUniform)
#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/camera.h"
#include "shared/path_tracer.h"
#include "shared/rng.h"

layout(local_size_x = kWorkgroupSize) in;

// Adds n to a 64-bit counter kept as (low, high): whichever addition carries the low word past
// 2^32 adds the carry, so concurrent additions count exactly.
void addToCounter(uint which, uint n) {
  uint before = which == 0u ? atomicAdd(queues.extensionRays[0], n) : atomicAdd(queues.shadowRays[0], n);
  if (before + n < before) {
    if (which == 0u) atomicAdd(queues.extensionRays[1], 1u);
    else atomicAdd(queues.shadowRays[1], 1u);
  }
}

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  uint pixel = pc.pixelOffset + path;
  uint rng = rngInit(pixel, pc.sampleIndex, pc.seed);
  vec2 jitter = vec2(rngNextFloat(rng), rngNextFloat(rng));
  vec3 direction = cameraRayDirection(camera, pixel % camera.width, pixel / camera.width, jitter);
  PathCounters rays;
  rays.extensionRays = 0u;
  rays.shadowRays = 0u;
  radiance[path] = tracePath(camera.position, direction, rng, pc.maxDepth, pc.lightCount, rays);
  // One pair of atomics per subgroup, not per path: both worker threads of lavapipe would otherwise
  // contend for the counters' cache line lane by lane (gpu/queue_append.glsl says what that cost
  // the shade pass).
  uint extensionRays = subgroupAdd(rays.extensionRays);
  uint shadowRays = subgroupAdd(rays.shadowRays);
  if (subgroupElect()) {
    addToCounter(0u, extensionRays);
    addToCounter(1u, shadowRays);
  }
}
