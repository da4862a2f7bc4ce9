// Pinhole camera rays: vertical field of view, aspect ratio from the image size, box pixel
// filter (a uniform jitter inside the pixel). Pixel (0, 0) is the top-left of the image.
#ifndef MIXTRACE_SHARED_CAMERA_H
#define MIXTRACE_SHARED_CAMERA_H
#include "shared/dialect.h"
#include "shared/floor_quotient.h"
#include "shared/layouts.h"
SHARED_BEGIN

// Pixel index (row-major, width pixels a row) -> (column, row), without an integer division
// (shared/floor_quotient.h): images have at most 16384 rows (kMaxImageSide), far below its limit.
SHARED_FN uvec2 cameraPixelCoords(uint pixel, uint width) {
  uint row = uint(floorQuotient(int(pixel), int(width)));
  return uvec2(pixel - row * width, row);
}

SHARED_FN vec3 cameraRayDirection(CameraGpu c, uint x, uint y, vec2 jitter) {
  float sx = (2.0f * (float(x) + jitter.x) / float(c.width) - 1.0f) * c.tanHalfFovY * c.aspect;
  float sy = (1.0f - 2.0f * (float(y) + jitter.y) / float(c.height)) * c.tanHalfFovY;
  return normalize(c.forward + sx * c.right + sy * c.up);
}

SHARED_END
#endif
