// Pixel index -> (column, row) (shaders/shared/camera.h cameraPixelCoords, compiled as C++): the
// float quotient with its one-row corrections equals integer division and remainder at both ends
// of every row, for ten widths between 1 and kMaxImageSide (small, odd, near 2^12 and the limit)
// and images of kMaxImageSide rows, where float(pixel) itself is no longer exact (above 2^24
// pixels).
#include <cstdint>

#include <gtest/gtest.h>

#include "session/options.h"
#include "shared/camera.h"

namespace {

using namespace mixtrace::shared;

TEST(CameraPixelCoords, EqualsIntegerDivisionAtEveryRowsEnds) {
  const uint32_t side = uint32_t(mixtrace::kMaxImageSide);
  for (uint32_t width : {1u, 2u, 3u, 7u, 320u, 641u, 4095u, 12345u, side - 1u, side}) {
    for (uint32_t row = 0; row < side; ++row) {
      const uint64_t start = uint64_t(row) * width;
      for (int64_t d : {int64_t(-1), int64_t(0), int64_t(1), int64_t(width) - 1}) {
        const int64_t p = int64_t(start) + d;
        if (p < 0 || p >= int64_t(uint64_t(side) * width)) continue;
        const uint32_t pixel = uint32_t(p);
        const glm::uvec2 xy = cameraPixelCoords(pixel, width);
        ASSERT_EQ(xy.x, pixel % width) << "pixel " << pixel << ", width " << width;
        ASSERT_EQ(xy.y, pixel / width) << "pixel " << pixel << ", width " << width;
      }
    }
  }
}

}  // namespace
