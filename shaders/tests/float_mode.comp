#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: a multiplication whose operands and results the host chooses, denormal or not
// (tests/float_mode_interface.h).
#include "tests/float_mode_interface.h"
#define PASS_BUFFERS FLOAT_MODE_BUFFERS
#define PASS_CONSTANTS FloatModeConstants
#include "gpu/buffers.glsl"
#include "shared/constants.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  throughput[i] = throughput[i] * pc.scale;
}
