#pragma once
// The wavefront path tracer on Vulkan: records the stages (generate, [intersect, shade,
// shadow] x depth, accumulate) as separate dispatches over queues in device memory; the sizes
// of later dispatches come from the queues' counters via vkCmdDispatchIndirect. The host only
// records and submits.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "output/image.h"
#include "render/gpu_scene.h"
#include "shared/bindings.h"
#include "cms/gpu_solver.h"
#include "cms/method_lights.h"
#include "render/renderer.h"
#include "scene/prepared_scene.h"
#include "vulkan/buffer.h"
#include "vulkan/pass_timer.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

class VulkanContext;

class WavefrontRenderer : public Renderer {
 public:
  // `lights` is the method's light data beside the scene (its selection table; the light clusters,
  // used when settings.cms.clusters: learned, cv, cms).
  WavefrontRenderer(VulkanContext& ctx, const PreparedScene& scene, const MethodLights& lights,
                    const RenderSettings& settings);
  ~WavefrontRenderer() override;

  void renderSamples(uint32_t count) override;
  uint32_t samplesPerPixel() const override { return spp_; }
  Image readImage(Image* standardError = nullptr) const override;
  RenderCounters counters() const override;
  std::map<std::string, double> passTimesMs() const override { return timer_.totalsMs(); }
  std::string deviceName() const override;

  // CMS: the cells as they are now (for tests and debug views). Empty for the other methods.
  struct CmsCellState {
    uint32_t clusters = 0;            // L
    std::vector<uint64_t> keys;       // per slot; 0 = unused
    std::vector<float> stats;         // per slot, cellStatsStride(L) floats (shared/cms_layouts.h)
    std::vector<uint32_t> samples;    // per slot
    std::vector<float> solution;      // per slot, cellSolutionStride(L) floats
    std::vector<float> defaults;      // L: the default selection
    shared::SolveParams params{};     // what the next solve runs with (cellCount = slots)
  };
  CmsCellState cmsCellState() const;

  // For the viewer (host/viewer): start accumulating again from `camera` (the film is cleared;
  // learned cells are world-space and stay), and the state its display pass reads.
  void restart(const shared::CameraGpu& camera);
  const DescriptorSet& descriptors() const { return set_; }
  void bindDisplay(const Buffer& display) { set_.bind(BINDING_DISPLAY, display); }
  uint32_t clusterCount() const { return clusterCount_; }
  const std::vector<uint32_t>& specialization() const { return spec_; }

 private:
  // `gathering`: this sample pass adds to the CMS statistics (the training schedule); its shade
  // and shadow passes are then timed apart, so the statistics' cost shows (benchmarks/suite.py).
  void recordSample(VkCommandBuffer cmd, uint32_t sampleIndex, uint32_t pixelOffset, uint32_t paths, bool gathering);
  // Clears the film and the first-hit cells (before the first sample, and on restart).
  void recordClearFilm(VkCommandBuffer cmd);
  // CMS, between training iterations: solve every cell from its statistics so far, and refresh
  // the pixel estimate the next iteration's statistics are weighted by.
  void recordSolve(VkCommandBuffer cmd, bool timed);
  shared::SolveParams solveParams() const;
  void dispatch(VkCommandBuffer cmd, const ComputePipeline& p, const shared::PassConstants& pc, uint32_t groups);
  // `label` names the pass in the GPU timings (default: the pipeline's name).
  void dispatchIndirect(VkCommandBuffer cmd, const ComputePipeline& p, const shared::PassConstants& pc, VkDeviceSize offset,
                        const char* label = nullptr);

  VulkanContext& ctx_;
  RenderSettings settings_;
  uint32_t lightCount_;
  uint32_t pixelCount_;
  uint32_t pathCount_;
  uint32_t spp_ = 0;
  uint32_t gatheringSamples_ = 0;   // CMS: sample passes that gathered statistics
  GpuScene scene_;
  Buffer lightSelection_;   // the method's LightSelectionGpu per light, beside the scene's lights
  DescriptorSet set_;
  Buffer rayOrigin_, rayDirection_, throughput_, radiance_, rng_, misPdf_, hits_, rayQueue_, shadowQueue_, queueState_, film_;
  // Controlled mixture sampling: cell table, statistics, solution, clusters, per-path state of the
  // previous vertex's BSDF sample. One-element placeholders when the method does not use them.
  bool casAtomics_ = false;   // CMS statistics through compare-and-swap loops, not the *_float_atomics variants
  uint32_t clusterCount_ = 0, cellTableSize_ = 1;
  glm::vec3 gridOrigin_{0.0f};
  float gridInvCellSize_ = 1.0f;
  Buffer cellKeys_, cellStats_, cellSamples_, cellSolution_, clusterDefaults_, clusters_, clusterLights_;
  Buffer cvState_, pixelEstimate_, firstCell_;
  Buffer displayPlaceholder_;   // bound until a viewer binds its display buffer
  std::vector<uint32_t> spec_;  // the pipelines' specialization constants
  std::unique_ptr<CellSolver> solver_;
  std::unique_ptr<ComputePipeline> pixelEstimatePass_;
  std::unique_ptr<ComputePipeline> generate_, prepare_, intersect_, shade_, shadow_, accumulate_;
  PassTimer timer_;
  VkFence fence_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

}  // namespace mixtrace
