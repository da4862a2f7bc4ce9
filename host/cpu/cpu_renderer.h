#pragma once
// The CPU reference: a straightforward path tracer, one path at a time, multithreaded over
// tiles. It exists to check the GPU path (queues, traversal, atomics), so its integrator loop is
// written independently of the wavefront orchestration; the material, sampling and traversal
// maths are the shared headers the GPU runs too (chi-square tested on their own).
// Statistics are accumulated in double precision.
#include <atomic>
#include <cstdint>
#include <vector>

#include "render/renderer.h"
#include "scene/prepared_scene.h"

namespace mixtrace {

class CpuRenderer : public Renderer {
 public:
  CpuRenderer(const PreparedScene& scene, const RenderSettings& settings);

  void renderSamples(uint32_t count) override;
  uint32_t samplesPerPixel() const override { return spp_; }
  Image readImage(Image* variance = nullptr) const override;
  RenderCounters counters() const override;
  std::map<std::string, double> passTimesMs() const override { return {}; }
  std::string deviceName() const override;

 private:
  struct PixelStats {
    double mean[3] = {0.0, 0.0, 0.0};
    double m2[3] = {0.0, 0.0, 0.0};  // sum of squared deviations (Welford)
  };
  void renderTile(uint32_t tile, uint32_t count, RenderCounters& local);

  const PreparedScene& scene_;
  RenderSettings settings_;
  shared::CameraGpu camera_;
  uint32_t lightCount_;
  uint32_t threads_;
  uint32_t spp_ = 0;
  std::vector<PixelStats> film_;
  RenderCounters counters_;
};

}  // namespace mixtrace
