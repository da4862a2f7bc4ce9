#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 1: one camera ray per path of the chunk; resets the path state and fills the first queue.
#include "wavefront/generate_interface.h"
#define PASS_BUFFERS GENERATE_BUFFERS
#define PASS_CONSTANTS GenerateConstants
#include "gpu/buffers.glsl"
#include "shared/camera.h"
#include "shared/rng.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  uint pixel = pc.pixelOffset + path;
  uint rng = rngInit(pixel, pc.sampleIndex, pc.seed);
  uvec2 xy = cameraPixelCoords(pixel, camera.width);
  vec2 jitter = vec2(rngNextFloat(rng), rngNextFloat(rng));
  rayOrigin[path] = camera.position;
  rayDirection[path] = cameraRayDirection(camera, xy.x, xy.y, jitter);
  throughput[path] = vec3(1.0);
  radiance[path] = vec3(0.0);
  misPdf[path] = 0.0;   // 0: the camera ray, whose emitter hits take no MIS weight
  rngState[path] = rng;
  rayQueue[path] = path;
  if (path == 0u) {
    queues.rayCount[0] = pc.pathCount;
    queues.rayCount[1] = 0u;
    queues.shadowCount = 0u;
  }
}
