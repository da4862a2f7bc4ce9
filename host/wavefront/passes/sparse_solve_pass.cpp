#include "wavefront/passes/sparse_solve_pass.h"

#include <algorithm>
#include <string>

#include "shared/bindings.h"
#include "shared/layouts.h"
#include "util/error.h"
#include "vulkan/context.h"
#include "vulkan/pass_timer.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

// SparseSolveConstants fits the guaranteed push-constant range: checked in vulkan/layout_checks.cpp.

GpuSparseSolver::GpuSparseSolver(VulkanContext& ctx) : ctx_(ctx) {
  for (uint32_t stage = 0; stage < shared::kSparseStageCount; ++stage) {
    static_assert(SPEC_SPARSE_STAGE >= SPEC_COUNT, "the stage id must follow the renderer's ids");
    std::vector<uint32_t> specialization(SPEC_SPARSE_STAGE + 1, 0u);   // the renderer's ids: unused here
    specialization[SPEC_SPARSE_STAGE] = stage;
    passes_.push_back(std::make_unique<ComputePass>(ctx, "sparse_solve", BINDINGS_OF(SPARSE_SOLVE_BUFFERS),
                                                    sizeof(shared::SparseSolveConstants), specialization));
  }
  args_ = Buffer(ctx_, 3 * sizeof(uint32_t), "CMS sparse solve dispatch arguments");
  reserve(1);
}

void GpuSparseSolver::reserve(uint32_t cells) {
  cells = std::max(cells, 1u);
  if (cells <= reservedCells_) return;
  scratch_ = Buffer(ctx_, VkDeviceSize(cells) * shared::kSparseScratchStride * sizeof(uint32_t), "CMS sparse solve scratch");
  reservedCells_ = cells;
  // The set still names the old scratch: forget the other bindings too, so that record() refuses
  // to run until bind() has written a complete set again.
  bound_.clear();
}

void GpuSparseSolver::bind(const BufferBindings& buffers) {
  bound_ = buffers;
  bound_[shared::BINDING_SPARSE_SCRATCH] = &scratch_;
  bound_[shared::BINDING_SPARSE_ARGS] = &args_;
  for (auto& pass : passes_) pass->bind(bound_);
}

void GpuSparseSolver::check(const SparseSolveSettings& s) const {
  if (s.clusterCount > shared::kMaxClusters)
    throw Error("CMS sparse solve: " + std::to_string(s.clusterCount) + " light clusters, at most " +
                std::to_string(shared::kMaxClusters) + " are supported");
  if (s.cellCount > reservedCells_)
    throw Error("CMS sparse solve: " + std::to_string(s.cellCount) + " cells, scratch reserved for " +
                std::to_string(reservedCells_));
  if (s.pairCapacity == 0 || (s.pairCapacity & (s.pairCapacity - 1)) != 0)
    throw Error("CMS sparse solve: pair table capacity " + std::to_string(s.pairCapacity) + " is not a power of two");
  if (bound_.empty()) throw Error("CMS sparse solve: recorded before bind() (or after reserve() grew the scratch)");
}

namespace {
// What the timings call each stage (shared/cms_sparse_solve.h), indexed by stage.
const char* const kStageLabels[shared::kSparseStageCount] = {
    "sparse_solve.init",  "sparse_solve.max",   "sparse_solve.mean",   "sparse_solve.ridge",  "sparse_solve.schur",
    "sparse_solve.pivot", "sparse_solve.alpha", "sparse_solve.finish", "sparse_solve.clear", "sparse_restart",
    "sparse_solve.args", "sparse_solve.remainder"};
}  // namespace

shared::SparseSolveConstants GpuSparseSolver::constants(const SparseSolveSettings& s) const {
  shared::SparseSolveConstants c{};
  c.cellCount = s.cellCount;
  c.clusterCount = s.clusterCount;
  c.pairCapacity = s.pairCapacity;
  c.minSamples = s.minSamples;
  c.minTechniqueSamples = s.minTechniqueSamples;
  c.flags = s.flags;
  c.ridge = s.ridge;
  c.maxGroupsX = ctx_.properties().limits.maxComputeWorkGroupCount[0];
  return c;
}

void GpuSparseSolver::stage(VkCommandBuffer cmd, const SparseSolveSettings& s, uint32_t stage, uint32_t items,
                            PassTimer* timer) const {
  const shared::SparseSolveConstants c = constants(s);
  // One invocation per item; workgroups beyond the device's limit in x wrap into y (the shader
  // computes the item from both), so a table of 2^22 slots fits lavapipe's 65535.
  const glm::uvec2 grid = shared::sparseDispatchGrid(workgroupsFor(items), c.maxGroupsX);
  if (grid.y > ctx_.properties().limits.maxComputeWorkGroupCount[1])
    throw Error("CMS sparse solve: " + std::to_string(items) + " items exceed the device's dispatch limits");
  passes_[stage]->dispatch(cmd, &c, sizeof(c), grid.x, grid.y);
  computeBarrier(cmd);
  if (timer) timer->mark(cmd, kStageLabels[stage]);
}

void GpuSparseSolver::pairStage(VkCommandBuffer cmd, const SparseSolveSettings& s, uint32_t stage,
                                PassTimer* timer) const {
  const shared::SparseSolveConstants c = constants(s);
  passes_[stage]->dispatchIndirect(cmd, &c, sizeof(c), args_, 0);
  computeBarrier(cmd);
  if (timer) timer->mark(cmd, kStageLabels[stage]);
}

void GpuSparseSolver::record(VkCommandBuffer cmd, const SparseSolveSettings& s, PassTimer* timer) const {
  check(s);
  if (s.cellCount == 0) return;
  const uint32_t cells = s.cellCount;
  stage(cmd, s, shared::kSparseInitCells, cells, timer);
  stage(cmd, s, shared::kSparsePairArgs, 1, timer);
  pairStage(cmd, s, shared::kSparseMaxPairs, timer);
  pairStage(cmd, s, shared::kSparseMeanPairs, timer);
  stage(cmd, s, shared::kSparseRidgeCells, cells, timer);
  pairStage(cmd, s, shared::kSparseSchurPairs, timer);
  stage(cmd, s, shared::kSparsePivotCells, cells, timer);
  pairStage(cmd, s, shared::kSparseAlphaPairs, timer);
  pairStage(cmd, s, shared::kSparseRemainderPairs, timer);
  stage(cmd, s, shared::kSparseFinishCells, cells, timer);
  pairStage(cmd, s, shared::kSparseClearPairs, timer);
}

void GpuSparseSolver::recordRestart(VkCommandBuffer cmd, const SparseSolveSettings& s, PassTimer* timer) const {
  check(s);
  if (s.cellCount == 0) return;
  // The arguments again: this step may be recorded without record() before it.
  stage(cmd, s, shared::kSparsePairArgs, 1, nullptr);
  pairStage(cmd, s, shared::kSparseRestartPairs, timer);
}

}  // namespace mixtrace
