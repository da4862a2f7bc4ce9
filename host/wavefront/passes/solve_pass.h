#pragma once
// The CMS solve pass (shaders/cms/solve.comp): between iterations, turns every cell's statistics
// into control-variate coefficients and a selection pmf. Owns its pipeline and its descriptor set
// of the buffers shaders/cms/solve_interface.h lists (the cell statistics, sample counts and
// solutions and the cluster defaults; sizes: shared/cms_layouts.h).
#include <vulkan/vulkan.h>

#include "cms/solve_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class VulkanContext;

class CellSolver {
 public:
  explicit CellSolver(VulkanContext& ctx);

  // The buffers to solve in: every row of SOLVE_BUFFERS, by binding number (they must outlive
  // the recorded commands). Binding again points the next recorded solve at others.
  void bind(const BufferBindings& buffers) { pass_.bind(buffers); }

  // Records the solve of params.cellCount cells followed by a compute barrier, so the next pass
  // reads the solution. Statistics written by earlier passes must already be visible (the
  // renderer's passes each end with a barrier). Throws mixtrace::Error when
  // params.clusterCount > shared::kMaxClusters.
  void record(VkCommandBuffer cmd, const shared::SolveParams& params) const;

 private:
  VulkanContext& ctx_;
  ComputePass pass_;
};

}  // namespace mixtrace
