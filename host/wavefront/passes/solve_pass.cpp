#include "wavefront/passes/solve_pass.h"

#include <algorithm>
#include <string>

#include "shared/layouts.h"
#include "util/error.h"
#include "vulkan/context.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

// SolveParams fits the guaranteed push-constant range: checked in vulkan/layout_checks.cpp.

CellSolver::CellSolver(VulkanContext& ctx)
    : ctx_(ctx), pass_(ctx, "solve", BINDINGS_OF(SOLVE_BUFFERS), sizeof(shared::SolveParams), {}) {}

void CellSolver::record(VkCommandBuffer cmd, const shared::SolveParams& params) const {
  if (params.clusterCount > shared::kMaxClusters)
    throw Error("CMS solve: " + std::to_string(params.clusterCount) + " light clusters, at most " +
                std::to_string(shared::kMaxClusters) + " are supported");
  if (params.cellCount == 0) return;
  // One invocation per cell. Workgroups beyond the device's limit in x wrap into y (the shader
  // computes the cell from both), so millions of cells fit.
  uint32_t groups = (params.cellCount + shared::kWorkgroupSize - 1) / shared::kWorkgroupSize;
  uint32_t maxX = ctx_.properties().limits.maxComputeWorkGroupCount[0];
  uint32_t groupsX = std::min(groups, maxX);
  uint32_t groupsY = (groups + groupsX - 1) / groupsX;
  if (groupsY > ctx_.properties().limits.maxComputeWorkGroupCount[1])
    throw Error("CMS solve: " + std::to_string(params.cellCount) + " cells exceed the device's dispatch limits");

  pass_.dispatch(cmd, &params, sizeof(params), groupsX, groupsY);
  computeBarrier(cmd);
}

}  // namespace mixtrace
