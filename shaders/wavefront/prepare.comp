#version 460
#extension GL_GOOGLE_include_directive : require
// A single invocation between stages: turns a queue's counter into indirect dispatch arguments
// (so the host never reads a count back) and resets the counters the next stage appends to.
#include "wavefront/prepare_interface.h"
#define PASS_BUFFERS PREPARE_BUFFERS
#define PASS_CONSTANTS PrepareConstants
#include "gpu/buffers.glsl"

layout(local_size_x = 1) in;


// 64-bit ray counters as two uints: a single invocation runs this, so the carry needs no atomics.
void addToCounter(inout uint counter[2], uint n) {
  uint low = counter[0] + n;
  if (low < counter[0]) counter[1] += 1u;
  counter[0] = low;
}

void main() {
  if (pc.queue == kPrepareRays) {
    uint n = queues.rayCount[pc.queueIn];
    queues.rayArgs.x = (n + kWorkgroupSize - 1u) / kWorkgroupSize;
    queues.rayArgs.y = 1u;
    queues.rayArgs.z = 1u;
    queues.rayCount[1u - pc.queueIn] = 0u;
    queues.shadowCount = 0u;
    queues.untracedShadows = 0u;
    queues.shadeCount = 0u;
    addToCounter(queues.extensionRays, n);
  } else if (pc.queue == kPrepareShade) {
    queues.shadeArgs.x = (queues.shadeCount + kWorkgroupSize - 1u) / kWorkgroupSize;
    queues.shadeArgs.y = 1u;
    queues.shadeArgs.z = 1u;
    addToCounter(queues.shadedRays, queues.shadeCount);
  } else {
    uint n = queues.shadowCount;
    addToCounter(queues.shadowRays, n - min(queues.untracedShadows, n));
    queues.shadowArgs.x = (n + kWorkgroupSize - 1u) / kWorkgroupSize;
    queues.shadowArgs.y = 1u;
    queues.shadowArgs.z = 1u;
  }
}
