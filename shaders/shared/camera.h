// Pinhole camera rays: vertical field of view, aspect ratio from the image size, box pixel
// filter (a uniform jitter inside the pixel). Pixel (0, 0) is the top-left of the image.
#ifndef MIXTRACE_SHARED_CAMERA_H
#define MIXTRACE_SHARED_CAMERA_H
#include "shared/dialect.h"
#include "shared/layouts.h"
SHARED_BEGIN

// Pixel index (row-major, width pixels a row) -> (column, row). The row is a float quotient
// corrected by one either way rather than an integer division: SIMD units have no integer
// division, so lavapipe divides lane by lane (the generate pass's costliest lines). The float
// estimate is within one row of the true one: its relative error is a few ulps (GLSL allows a
// division 2.5 ulp off), so the error in rows stays below 1 for any row below 2^21, and images
// have at most 16384 rows (kMaxImageSide).
SHARED_FN uvec2 cameraPixelCoords(uint pixel, uint width) {
  int row = int(floor(float(pixel) / float(width)));
  int rest = int(pixel) - row * int(width);
  if (rest < 0) --row;
  if (rest >= int(width)) ++row;
  return uvec2(pixel - uint(row) * width, uint(row));
}

SHARED_FN vec3 cameraRayDirection(CameraGpu c, uint x, uint y, vec2 jitter) {
  float sx = (2.0f * (float(x) + jitter.x) / float(c.width) - 1.0f) * c.tanHalfFovY * c.aspect;
  float sy = (1.0f - 2.0f * (float(y) + jitter.y) / float(c.height)) * c.tanHalfFovY;
  return normalize(c.forward + sx * c.right + sy * c.up);
}

SHARED_END
#endif
