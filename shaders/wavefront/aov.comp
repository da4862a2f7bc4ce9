#version 460
#extension GL_GOOGLE_include_directive : require
// After the first intersection: each path's first hit into its pixel's running means of albedo,
// shading normal and depth (--aov). One path per pixel per sample pass, so no atomics.
#include "wavefront/aov_interface.h"
#define PASS_BUFFERS AOV_BUFFERS
#define PASS_UNREAD_BUFFERS AOV_UNREAD_BUFFERS
#define PASS_CONSTANTS AovConstants
#include "gpu/buffers.glsl"
// It reads surfaces only, never a light's pmf.
#define EMITTERS_UNIFORM false
#include "shared/first_hit_aov.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  FirstHitAov a = firstHitAov(hits[path], rayDirection[path]);
  uint base = kAovStride * (pc.pixelOffset + path);
  float w = 1.0 / float(pc.sampleIndex + 1u);
  aov[base + kAovAlbedo] += (a.albedo - aov[base + kAovAlbedo]) * w;
  aov[base + kAovNormal] += (a.normal - aov[base + kAovNormal]) * w;
  aov[base + kAovDepth] += (vec3(a.depth, 0.0, 0.0) - aov[base + kAovDepth]) * w;
}
