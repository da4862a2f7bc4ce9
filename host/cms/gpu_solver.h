#pragma once
// The CMS solve pass (shaders/cms/solve.comp): between iterations, turns every cell's statistics
// into control-variate coefficients and a selection pmf. Owns its pipeline; the buffers are the
// ones bound to the shared descriptor set at BINDING_CELL_STATS, BINDING_CELL_SAMPLES,
// BINDING_CELL_SOLUTION and BINDING_CLUSTER_DEFAULTS (sizes: shared/cms_layouts.h).
#include <vulkan/vulkan.h>

#include "shared/cms_layouts.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

class VulkanContext;

class CellSolver {
 public:
  // `set` must outlive the solver; its push-constant range must hold SolveParams.
  CellSolver(VulkanContext& ctx, DescriptorSet& set);

  // Records the solve of params.cellCount cells followed by a compute barrier, so the next pass
  // reads the solution. Statistics written by earlier passes must already be visible (the
  // renderer's passes each end with a barrier). Throws mixtrace::Error when
  // params.clusterCount > shared::kMaxClusters.
  void record(VkCommandBuffer cmd, const shared::SolveParams& params) const;

 private:
  VulkanContext& ctx_;
  DescriptorSet& set_;
  ComputePipeline pipeline_;
};

}  // namespace mixtrace
