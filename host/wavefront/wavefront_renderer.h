#pragma once
// The wavefront path tracer on Vulkan: records the passes (generate, [prepare, intersect, shade,
// prepare, shadow] x depth, accumulate; host/wavefront/passes/, one file each) as separate dispatches
// over queues in device memory; the sizes of later dispatches come from the queues' counters via
// vkCmdDispatchIndirect. The renderer owns the buffers (wavefront/device_buffers.h, from the tables
// of shaders/shared/) and orchestrates: it calls the passes in order and submits.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "wavefront/passes/solve_pass.h"
#include "cms/method_lights.h"
#include "output/image.h"
#include "wavefront/device_buffers.h"
#include "wavefront/gpu_scene.h"
#include "wavefront/passes/accumulate_pass.h"
#include "wavefront/passes/aov_pass.h"
#include "wavefront/passes/fused_pass.h"
#include "wavefront/passes/generate_pass.h"
#include "wavefront/passes/intersect_pass.h"
#include "wavefront/passes/pixel_estimate_pass.h"
#include "wavefront/passes/prepare_pass.h"
#include "wavefront/passes/shade_pass.h"
#include "wavefront/passes/shadow_pass.h"
#include "backend/renderer.h"
#include "scene/prepared_scene.h"
#include "shared/bindings.h"
#include "vulkan/buffer.h"
#include "vulkan/pass_timer.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

// Declared only: its header brings the sparse solve's shared GLSL-compatible headers, which a
// includer of this one may compile with accessors of its own (tests/gpu/cms_solve_test.cpp).
class GpuSparseSolver;
struct SparseSolveSettings;

class VulkanContext;

// Whether --schedule fused can run these settings: every method, without AOVs.
bool fusedScheduleRuns(const RenderSettings& settings);

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
  AovImages readAovs() const override;
  RenderCounters counters() const override;
  std::map<std::string, double> passTimesMs() const override { return timer_.totalsMs(); }
  std::string deviceName() const override;
  double setupSecondsDuringRender() const override { return fusedBuildSeconds_; }
  // Whether the fused kernel's pipeline exists: with --schedule auto only once the render chose it.
  bool fusedPassBuilt() const { return fused_ != nullptr; }

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
  // learned cells are world-space and stay), and the state its display pass reads: every buffer
  // by binding number (the film, the first-hit cells, the cells' data...), to bind, not to write.
  void restart(const shared::CameraGpu& camera);
  const BufferBindings& buffers() const { return bindings_; }
  uint32_t clusterCount() const { return clusterCount_; }
  const std::vector<uint32_t>& specialization() const { return spec_; }

 private:
  // One sample pass over one chunk of paths. `gathering`: it adds to the CMS statistics (the
  // training schedule).
  void recordSample(VkCommandBuffer cmd, uint32_t sampleIndex, uint32_t pixelOffset, uint32_t paths, bool gathering);
  // Clears the film and the first-hit cells (before the first sample, and on restart).
  void recordClearFilm(VkCommandBuffer cmd);
  // CMS, between training iterations: solve every cell from its statistics so far, and refresh
  // the pixel estimate the next iteration's statistics are weighted by.
  void recordSolve(VkCommandBuffer cmd, bool timed);
  shared::SolveParams solveParams() const;
  SparseSolveSettings sparseSolveSettings(const shared::SolveParams& params) const;
  void reportPairs(RenderCounters& counters) const;   // the control variate's fields of the stats JSON
  uint32_t solveMarks() const;                         // timer marks one recordSolve(timed) adds
  const Buffer& buffer(uint32_t binding) const { return buffers_[binding]; }

  VulkanContext& ctx_;
  RenderSettings settings_;
  uint32_t lightCount_;
  bool lightBvh_ = false;   // the method picks lights by its light BVH (pt-bvh)
  // Intersect queues the rays that hit something for the shade pass, which then never runs a SIMD
  // group for rays that escaped (IntersectConstants.queueForShade). Only where escaped rays end
  // their paths (no environment, no CMS terms to settle), and only while enough of them escape:
  // the first submission measures it (decideShadeQueue).
  bool queueForShade_ = false;
  void decideShadeQueue(const shared::QueueState& q);
  // The fused schedule's pass records the sample passes (--schedule fused, or auto's choice); with
  // auto on a CPU device the first submission runs the wavefront and measures the extension rays
  // its paths traced per path and depth (decideSchedule; -1 until then).
  bool useFused_ = false;
  bool autoSchedule_ = false;
  double rayOccupancy_ = -1.0;
  void decideSchedule(const shared::QueueState& q);
  void buildFusedPass();   // fused_, once useFused_ (not at set-up for auto: it may keep the wavefront)
  double fusedBuildSeconds_ = 0.0;   // what that took inside renderSamples (setupSecondsDuringRender)
  // Both decisions read the counters of the first submission, in one read-back.
  bool probed_ = false;
  void decideFromFirstSubmission();
  // The members the shade, shadow and fused passes' constants share, by name (gpu/cms_statistics.glsl
  // reads them from either): VertexConstants or FusedConstants.
  template <class Constants>
  Constants vertexConstants(uint32_t paths, uint32_t pixelOffset, bool gathering) const;
  LightSelection lightSelection_ = LightSelection::Power;   // the method's (VertexConstants)
  uint32_t pixelCount_;
  uint32_t pathCount_;
  uint32_t spp_ = 0;
  uint32_t gatheringSamples_ = 0;   // CMS: sample passes that gathered statistics
  GpuScene scene_;
  // Controlled mixture sampling: the cell grid. Its buffers are placeholders of one element when
  // the method does not use them (shared/cms_state.h).
  bool casAtomics_ = false;   // CMS statistics through compare-and-swap loops, not the *_float_atomics variants
  bool floatAtomicVariants_ = false;   // the passes that add statistics use the *_float_atomics modules
  uint32_t clusterCount_ = 0, cellTableSize_ = 1;
  // The per-triangle control variate (shared/cms_pair_state.h): the pair table's capacity (1: the
  // placeholders of the other methods) and the techniques' counts for the stats JSON.
  bool pairTechniques_ = false;
  uint32_t pairCapacity_ = 1, techniqueCount_ = 0, emitterCount_ = 0;
  bool techniquesMerged_ = false;
  glm::vec3 gridOrigin_{0.0f};
  float gridInvCellSize_ = 1.0f;
  DeviceBuffers buffers_;
  BufferBindings bindings_;     // buffers_ and the scene's, by binding number: what the passes bind
  std::vector<uint32_t> spec_;  // the pipelines' specialization constants
  std::unique_ptr<CellSolver> solver_;
  std::unique_ptr<GpuSparseSolver> sparseSolver_;   // the per-triangle CV's step 1 and 3 (recordSolve)
  std::unique_ptr<PixelEstimatePass> pixelEstimatePass_;
  std::unique_ptr<GeneratePass> generate_;
  std::unique_ptr<PreparePass> prepare_;
  std::unique_ptr<IntersectPass> intersect_;
  std::unique_ptr<ShadePass> shade_;
  std::unique_ptr<ShadowPass> shadow_;
  std::unique_ptr<AccumulatePass> accumulate_;
  std::unique_ptr<AovPass> aov_;   // only where the render writes AOVs
  std::unique_ptr<FusedPass> fused_;   // the fused schedule's pass, built once useFused_ (buildFusedPass)
  PassTimer timer_;
  // The most timestamps one sample pass (all chunks, and the solve after it) has recorded so far:
  // what the next one is assumed to need when a submission is filled (renderSamples).
  uint32_t marksPerSample_ = 0;
  VkFence fence_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

}  // namespace mixtrace
