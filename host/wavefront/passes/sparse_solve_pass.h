#pragma once
// The sparse CMS solve pass (shaders/cms/sparse_solve.comp; stages, scratch and rules:
// shaders/shared/cms_sparse_solve.h): between iterations, solves every cell's arrowhead system over
// its (cell, technique) pairs, one control-variate technique per emissive triangle, and writes
// alpha_t per pair (PAIR_ALPHA) and alpha_B, validity and sum of alpha per cell (the cell
// solution's solutionAlphaB, solutionValid, solutionAlphaSum). The float twin of the double
// solveSparseCell (host/cms/sparse_solve.h); tests/gpu/cms_sparse_solve_test.cpp holds the two
// together.
//
// Between iterations the caller records, in this order:
//   1. record():        the sparse solve (writes the control variate of every cell);
//   2. CellSolver::record() with shared::kSolveKeepControlVariate (it leaves the three solution
//      slots above as step 1 wrote them): selection, and the restart of a cell whose selection
//      changed (its statistics and CELL_SAMPLES = 0). Step 1 must come first: it reads the cell's
//      A_BB, b_B and CELL_SAMPLES before this step may reset them;
//   3. recordRestart(): zeroes the pair statistics and sample counts of every restarted cell.
// Owns its pipelines (one per stage), their descriptor sets and the per-cell scratch (binding 43).
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "cms/sparse_solve_interface.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class PassTimer;
class VulkanContext;

struct SparseSolveSettings {
  uint32_t cellCount = 0;
  uint32_t clusterCount = 0;          // L of the cell statistics and solutions
  uint32_t pairCapacity = 0;          // slots of the pair table: a power of two
  uint32_t minSamples = 64;           // per cell (CELL_SAMPLES)
  uint32_t minTechniqueSamples = 1;   // per pair (PAIR_SAMPLES)
  float ridge = 1e-3f;                // relative to the mean diagonal of the techniques in the system
  uint32_t flags = 0;                 // shared::kSolveControlVariate: use the solution; else zeros, invalid
};

class GpuSparseSolver {
 public:
  explicit GpuSparseSolver(VulkanContext& ctx);

  // Sizes the scratch for `cells` cells (kept when large enough). When it grows, bind() must follow
  // before the next record(); never while a recorded solve is in flight.
  void reserve(uint32_t cells);
  uint32_t reservedCells() const { return reservedCells_; }
  size_t scratchBytes() const { return (reservedCells_ ? scratch_.size() : 0) + args_.size(); }

  // The buffers: every row of SPARSE_SOLVE_BUFFERS but the scratch and the dispatch arguments (its
  // own), by binding number; PAIR_OCCUPIED lists the slots the pair stages visit;
  // they must outlive the recorded commands.
  void bind(const BufferBindings& buffers);

  // Records the solve (step 1 above), its stages separated by compute barriers and followed by
  // one, so the next pass reads the solution. Statistics written by earlier passes must already be
  // visible. With a timer, marks each stage ("sparse_solve.<stage>": 10 marks). Throws mixtrace::Error
  // for more cells than reserved, a capacity that is not a power of two, L > kMaxClusters, or
  // counts beyond the device's dispatch limits.
  void record(VkCommandBuffer cmd, const SparseSolveSettings& settings, PassTimer* timer = nullptr) const;
  // Step 3: the pair restart, followed by a barrier (marks "sparse_restart" with a timer).
  void recordRestart(VkCommandBuffer cmd, const SparseSolveSettings& settings, PassTimer* timer = nullptr) const;

 private:
  void check(const SparseSolveSettings& settings) const;
  shared::SparseSolveConstants constants(const SparseSolveSettings& settings) const;
  // A cell stage (or kSparsePairArgs), `items` invocations.
  void stage(VkCommandBuffer cmd, const SparseSolveSettings& settings, uint32_t stage, uint32_t items,
             PassTimer* timer) const;
  // A pair stage: one invocation per occupied slot, dispatched from args_.
  void pairStage(VkCommandBuffer cmd, const SparseSolveSettings& settings, uint32_t stage, PassTimer* timer) const;

  VulkanContext& ctx_;
  std::vector<std::unique_ptr<ComputePass>> passes_;   // one per stage (SPEC_SPARSE_STAGE)
  Buffer scratch_;
  Buffer args_;   // the pair stages' VkDispatchIndirectCommand (binding 45, kSparsePairArgs writes it)
  uint32_t reservedCells_ = 0;
  BufferBindings bound_;
};

}  // namespace mixtrace
