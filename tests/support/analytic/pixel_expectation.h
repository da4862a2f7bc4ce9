#pragma once
// Per-pixel expected values for a scene seen through the pinhole with a box filter: the pixel
// mean is the average of the radiance over the pixel's square. A pixel whose whole square sees
// one surface (or nothing) gets that average by a 2x2 Gauss rule, exact enough for radiance that
// varies smoothly across a pixel; a pixel that straddles an edge between surfaces is left out.
#include <cmath>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/analytic/pinhole.h"
#include "support/analytic/pixel_ztest.h"

namespace mixtrace::testing::analytic {

// The scene's triangles and, for each, the surface it belongs to (what the radiance callback
// distinguishes: a plane, an emitter, ...).
struct LabelledScene {
  std::vector<Tri> triangles;
  std::vector<int> surface;
  void add(const std::vector<Tri>& tris, int label) {
    triangles.insert(triangles.end(), tris.begin(), tris.end());
    surface.insert(surface.end(), tris.size(), label);
  }
};

// radiance(surface, hit, ray): the radiance arriving at the camera along `ray`, which first hits
// `hit` on `surface`; surface -1 (the ray leaves the scene) contributes `background` (a uniform
// environment's radiance; 0 without one) without a call.
using RadianceFn = std::function<glm::dvec3(int surface, const Hit& hit, const Ray& ray)>;

inline Expectation pixelExpectation(const CameraSpec& camera, int width, int height, const LabelledScene& scene,
                                    const RadianceFn& radiance, glm::dvec3 background = glm::dvec3(0.0)) {
  Expectation e(width, height);
  constexpr int kProbe = 5;  // probe grid per pixel side, corners included, to find edges
  const double g = 0.5 / std::sqrt(3.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int label = -2;
      bool uniform = true;
      for (int j = 0; j < kProbe && uniform; ++j)
        for (int i = 0; i < kProbe && uniform; ++i) {
          const Hit h = closestHit(scene.triangles,
                                   cameraRay(camera, width, height, x + i / (kProbe - 1.0), y + j / (kProbe - 1.0)));
          const int s = h.triangle < 0 ? -1 : scene.surface[size_t(h.triangle)];
          if (label == -2) label = s;
          uniform = s == label;
        }
      const size_t p = size_t(y) * width + x;
      if (!uniform) {
        e.tested[p] = 0;
        continue;
      }
      glm::dvec3 sum = label == -1 ? background : glm::dvec3(0.0);
      if (label >= 0) {
        for (double oy : {0.5 - g, 0.5 + g})
          for (double ox : {0.5 - g, 0.5 + g}) {
            const Ray r = cameraRay(camera, width, height, x + ox, y + oy);
            const Hit h = closestHit(scene.triangles, r);
            if (h.triangle >= 0) sum += 0.25 * radiance(scene.surface[size_t(h.triangle)], h, r);
          }
      }
      for (int c = 0; c < 3; ++c) e.value.rgb[3 * p + c] = float(sum[c]);
    }
  return e;
}

}  // namespace mixtrace::testing::analytic
