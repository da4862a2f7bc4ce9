// The pixel estimate CMS weights relate to (shared/pixel_estimate.h): per channel, the largest
// running mean in a (2r+1)^2 window, clamped at the image border, so that no pixel next to a
// bright one is taken for black.
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

namespace pixel_estimate_test {
const glm::vec3* gFilm = nullptr;
}
#define FILM_MEAN(i) (::pixel_estimate_test::gFilm[i])
#include "shared/pixel_estimate.h"

using mixtrace::shared::kPixelEstimateRadius;
using mixtrace::shared::pixelEstimateAt;

TEST(PixelEstimate, WindowMaximumPerChannelClampedAtTheBorder) {
  const int w = 9, h = 7, r = kPixelEstimateRadius;
  std::vector<glm::vec3> film(w * h, glm::vec3(0.01f, 0.02f, 0.03f));
  film[3 * w + 4] = glm::vec3(5.0f, 0.0f, 0.0f);   // a red highlight at (4, 3)
  film[0] = glm::vec3(0.0f, 0.0f, 7.0f);           // a blue one in the corner
  pixel_estimate_test::gFilm = film.data();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 e = pixelEstimateAt(x, y, w, h);
      bool nearRed = std::abs(x - 4) <= r && std::abs(y - 3) <= r;
      bool nearBlue = x <= r && y <= r;
      EXPECT_EQ(e.x, nearRed ? 5.0f : 0.01f) << x << "," << y;
      EXPECT_EQ(e.y, 0.02f) << x << "," << y;   // the highlights' 0 never lowers a channel
      EXPECT_EQ(e.z, nearBlue ? 7.0f : 0.03f) << x << "," << y;
    }
}

TEST(PixelEstimate, OnePixelImage) {
  std::vector<glm::vec3> film = {glm::vec3(0.5f, 0.25f, 0.0f)};
  pixel_estimate_test::gFilm = film.data();
  glm::vec3 e = pixelEstimateAt(0, 0, 1, 1);
  EXPECT_EQ(e, film[0]);
}
