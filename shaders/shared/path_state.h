// The wavefront's path state (a structure of arrays, one entry per path of a chunk), its queues
// and the film: every buffer the renderer allocates for the plain path tracer, declared once.
// Rows in the format of shared/buffer_table.h; the renderer allocates and binds them in one loop
// (host/wavefront/device_buffers.cpp).
#ifndef MIXTRACE_SHARED_PATH_STATE_H
#define MIXTRACE_SHARED_PATH_STATE_H
#include "shared/buffer_table.h"
#include "shared/layouts.h"

#define BUFFER_RAY_ORIGIN(X) X(RAY_ORIGIN, rayOrigin, 9, READ_WRITE, vec3, PER_PATH, "path state (ray origins)")
#define BUFFER_RAY_DIRECTION(X) \
  X(RAY_DIRECTION, rayDirection, 10, READ_WRITE, vec3, PER_PATH, "path state (ray directions)")
#define BUFFER_THROUGHPUT(X) X(THROUGHPUT, throughput, 11, READ_WRITE, vec3, PER_PATH, "path state (throughput)")
#define BUFFER_RADIANCE(X) X(RADIANCE, radiance, 12, READ_WRITE, vec3, PER_PATH, "path state (radiance)")
#define BUFFER_RNG(X) X(RNG, rngState, 13, READ_WRITE, uint, PER_PATH, "path state (random numbers)")
#define BUFFER_MIS_PDF(X) X(MIS_PDF, misPdf, 14, READ_WRITE, float, PER_PATH, "path state (MIS pdfs)")
// The geometric normal of the vertex a BSDF sample left (method pt-bvh): the light BVH's pmf of an
// emitter it hits depends on the vertex's point (rayOrigin) and normal.
#define BUFFER_MIS_NORMAL(X) X(MIS_NORMAL, misNormal, 33, READ_WRITE, vec3, PER_PATH, "path state (MIS normals)")
#define BUFFER_HITS(X) X(HITS, hits, 15, READ_WRITE, HitRecord, PER_PATH, "path state (hits)")
// Queues: the extension rays' path indices in ping-pong thirds of pathCount entries each, and in
// the third (kShadeQueue) the shade queue: this depth's rays that hit something, compacted by
// intersect where the renderer has it queue them (IntersectConstants.queueForShade: no
// environment lights the others and no CMS terms wait for them, so their paths end unshaded);
// the shadow rays; and the counters with the indirect dispatch arguments.
#define BUFFER_RAY_QUEUE(X) X(RAY_QUEUE, rayQueue, 16, READ_WRITE, uint, THREE_PER_PATH, "ray queues")
// One record per path and depth; two with the per-triangle control variate (a light sample and
// the previous BSDF sample's pair terms: shaders/wavefront/shade_interface.h).
#define BUFFER_SHADOW_QUEUE(X) X(SHADOW_QUEUE, shadowQueue, 17, READ_WRITE, ShadowRay, SHADOW_SLOTS, "shadow-ray queue")
#define BUFFER_QUEUE_STATE(X) X(QUEUE_STATE, queues, 18, READ_BACK, QueueState, ONE, "queue counters")
// Per pixel: [2 * pixel] the running mean, [2 * pixel + 1] sqrt of the sum of squared deviations
// (shared/film.h).
#define BUFFER_FILM(X) X(FILM, film, 19, READ_BACK, vec3, TWO_PER_PIXEL, "film")
// The first hit's albedo, normal and depth per pixel (shared/first_hit_aov.h); one element
// unless the render writes them (--aov).
#define BUFFER_AOV(X) X(AOV, aov, 49, READ_BACK, vec3, AOV_PIXELS, "AOVs")

#define PATH_STATE_BUFFERS(X)                                                                             \
  BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_THROUGHPUT(X) BUFFER_RADIANCE(X) BUFFER_RNG(X)     \
  BUFFER_MIS_PDF(X) BUFFER_HITS(X) BUFFER_RAY_QUEUE(X) BUFFER_SHADOW_QUEUE(X) BUFFER_QUEUE_STATE(X) \
  BUFFER_FILM(X) BUFFER_MIS_NORMAL(X) BUFFER_AOV(X)

SHARED_BEGIN
PATH_STATE_BUFFERS(BUFFER_BINDING_CONSTANT)
SHARED_END
#endif
