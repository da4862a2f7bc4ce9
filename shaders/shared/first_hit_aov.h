// The auxiliary images a denoiser takes (--aov): per pixel, averaged over its samples like the
// image, the first hit's albedo (the base colour with textures and vertex colour: the surface's
// reflectance as Open Image Denoise expects it), its shading normal (world space, on the camera's
// side) and its distance from the camera. A camera ray that hits nothing gives 0 for all three.
// One source for the Vulkan AOV pass (wavefront/aov.comp) and the CPU backend.
// Their buffer's layout: shared/aov_layout.h.
#ifndef MIXTRACE_SHARED_FIRST_HIT_AOV_H
#define MIXTRACE_SHARED_FIRST_HIT_AOV_H
#include "shared/aov_layout.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/surface.h"
SHARED_BEGIN_WITH_BUFFERS

struct FirstHitAov {
  vec3 albedo;
  vec3 normal;
  float depth;
};

// `direction`: the camera ray's (any length; the distance is along it in scene units).
SHARED_FN FirstHitAov firstHitAov(HitRecord hit, vec3 direction) {
  FirstHitAov a;
  a.albedo = vec3(0.0f);
  a.normal = vec3(0.0f);
  a.depth = 0.0f;
  if (hit.triangle == kNoHit) return a;
  SurfaceHit h = makeSurfaceHit(hit.triangle, hit.u, hit.v, direction);
  a.albedo = surfaceBsdf(h, surfaceMaterial(h)).baseColor;
  a.normal = h.shadingNormal;
  a.depth = hit.t * length(direction);
  return a;
}

SHARED_END_WITH_BUFFERS
#endif
