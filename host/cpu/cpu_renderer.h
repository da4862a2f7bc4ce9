#pragma once
// The CPU reference: a straightforward path tracer, one path at a time, multithreaded over
// tiles. It exists to check the GPU path (queues, traversal, atomics), so its integrator loop is
// written independently of the wavefront orchestration; the material, sampling and traversal
// maths are the shared headers the GPU runs too (chi-square tested on their own).
// Statistics are accumulated in double precision.
//
// The pt-* methods trace each tile's pixels sample after sample. Controlled mixture sampling
// (learned, cv, cms: cpu/cpu_cms_path.h, cpu/cpu_cms_cells.h) renders sample-major instead, one
// sample index for all pixels, then the next, because the cells are solved between sample indices:
// after samples 1, 3, 7, 15, ... (training iterations of doubling length), as the Vulkan renderer.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "cms/method_lights.h"
#include "cpu/cpu_cms_cells.h"
#include "backend/renderer.h"
#include "cpu/cpu_kernel_context.h"
#include "scene/prepared_scene.h"

namespace mixtrace {

class CpuRenderer : public Renderer {
 public:
  // `lights` is the method's light data beside the scene (its selection table; the light clusters,
  // used when settings.cms.clusters); a scene without lights has no clusters and then renders as
  // the plain path tracer, as on the GPU. Both are read while rendering: they must outlive this.
  CpuRenderer(const PreparedScene& scene, const MethodLights& lights, const RenderSettings& settings);

  void renderSamples(uint32_t count) override;
  uint32_t samplesPerPixel() const override { return spp_; }
  Image readImage(Image* standardError = nullptr) const override;
  AovImages readAovs() const override;
  RenderCounters counters() const override;
  std::map<std::string, double> passTimesMs() const override { return {}; }
  std::string deviceName() const override;

 private:
  struct PixelStats {
    double mean[3] = {0.0, 0.0, 0.0};
    double m2[3] = {0.0, 0.0, 0.0};  // sum of squared deviations (Welford)
  };
  void renderTile(uint32_t tile, uint32_t count, RenderCounters& local);
  // Runs renderTile(tile, count) over all tiles on the worker threads and adds up their counters.
  void renderPass(uint32_t count);
  // The running means as floats (what the GPU's film holds), for the CMS pixel estimate.
  std::vector<glm::vec3> filmMeans() const;

  const PreparedScene& scene_;
  const MethodLights& lights_;
  RenderSettings settings_;
  shared::CameraGpu camera_;
  uint32_t lightCount_;
  uint32_t threads_;
  uint32_t spp_ = 0;
  std::vector<PixelStats> film_;
  std::vector<glm::dvec3> aovs_;       // --aov: kAovStride running means per pixel (shared/aov_layout.h)
  RenderCounters counters_;
  std::unique_ptr<CpuCmsCells> cms_;   // null for the pt-* methods
  CpuKernelContext kernel_;            // the scene and cms_, bound by each worker thread
};

}  // namespace mixtrace
