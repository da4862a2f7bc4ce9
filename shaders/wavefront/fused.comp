#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The interface's CMS rows (shared/cms_state.h, cms_pair_state.h) name 64-bit keys.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// The fused schedule (fused_interface.h): each invocation draws its pixel's camera ray as
// generate.comp does and traces the whole path, then leaves its radiance for accumulate.comp:
// shared/path_tracer.h (the CPU backend's loop) for the methods without learning, and
// shared/cms_path_tracer.h (the CPU backend's too) for those with controlled mixture sampling,
// whose statistics it adds as the shade and shadow passes do (gpu/cms_statistics.glsl). The
// specialization constant CMS_SELECTION keeps one of the two in a pipeline.
#include "wavefront/fused_interface.h"
#define PASS_BUFFERS FUSED_BUFFERS
#define PASS_PAIR_BUFFERS 1
#define PASS_CONSTANTS FusedConstants
#define PASS_READS_SOLUTION_VIEWS
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"
#define LIGHT_BVH(i) LIGHT_BVH_FROM_TEXELS(i)
#define LIGHT_SELECT_BVH (LIGHT_SELECTION == kLightSelectBvh)
#define EMITTERS_UNIFORM (LIGHT_SELECTION == kLightSelectUniform)
#include "gpu/cms_statistics.glsl"
#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/camera.h"
#include "shared/path_tracer.h"
#define CMS_PATH_WEIGHT(cell, beta, pixel) sampleWeight(beta, (pixel) - pc.pixelOffset, cell)
#define CMS_PATH_COUNT_VERTEX(cell) countCellVertex(cell)
#include "shared/cms_path_tracer.h"
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

// The cell table and method of this render, for shared/cms_path_tracer.h.
CmsPathSetup cmsPathSetup(uint pixel) {
  CmsPathSetup c;
  c.grid = pushedCellGrid();
  c.clusterCount = pc.clusterCount;
  c.controlVariate = CMS_CONTROL_VARIATE;
  c.pairTechniques = CMS_PAIR_TECHNIQUES;
  c.pairCapacity = pc.pairCapacity;
  c.emitterCount = pc.emitterCount;
  c.maxDepth = pc.maxDepth;
  c.lightCount = pc.lightCount;
  c.pixel = pixel;
  return c;
}

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  uint pixel = pc.pixelOffset + path;
  uint rng = rngInit(pixel, pc.sampleIndex, pc.seed);
  uvec2 xy = cameraPixelCoords(pixel, camera.width);
  vec2 jitter = vec2(rngNextFloat(rng), rngNextFloat(rng));
  vec3 direction = cameraRayDirection(camera, xy.x, xy.y, jitter);
  PathCounters rays;
  rays.extensionRays = 0u;
  rays.shadowRays = 0u;
  if (CMS_SELECTION) {
    uint cell;
    radiance[path] = traceCmsPath(cmsPathSetup(pixel), camera.position, direction, rng, rays, cell);
    firstCell[pixel] = cell;
  } else {
    radiance[path] = tracePath(camera.position, direction, rng, pc.maxDepth, pc.lightCount, rays);
  }
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
