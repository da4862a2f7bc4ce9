#pragma once
// The controlled-mixture-sampling state of the CPU reference (docs/estimator.md): the hashed cell
// table, each cell's statistics in double precision, its sample count and its solution, the light
// clusters, and the pixel estimate the relative weights divide by. It follows the Vulkan renderer
// (wavefront/wavefront_renderer.cpp, shaders/wavefront/shade.comp, shadow.comp) rule for rule; only
// the statistics and the solve (cms/reference_solve.h) are double precision.
//
// Threading: many workers trace paths at once. They claim cells with a 64-bit compare-and-swap
// (shared/cms_cells.h, as the GPU does) and add to the statistics with atomic compare-exchange
// loops on doubles, so a cell's sums do not depend on which thread added what (up to the order of
// the additions). The solution, the defaults and the pixel estimate are only read while tracing;
// solveAll() and refreshPixelEstimate() run between sample passes, with no worker active.
//
// The shared headers reach this state through the macros of cpu/cpu_kernel_access.h, which also
// forms the statistics' terms (shared/cms_vertex_terms.h).
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "cms/cell_grid.h"
#include "cms/cms_setup.h"
#include "backend/renderer.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_state.h"
#include "shared/layouts.h"

namespace mixtrace {

class CpuCmsCells {
 public:
  // Solves the empty statistics once, as the Vulkan renderer's constructor does: every cell starts
  // with the default selection and no control variate.
  CpuCmsCells(const CmsScene& cms, const Bounds& sceneBounds, const RenderSettings& settings, uint32_t pixelCount);

  uint32_t clusterCount() const { return L_; }
  const CellGridSetup& grid() const { return grid_; }
  bool controlVariate() const { return controlVariate_; }
  // Whether the control variate's coefficients are per technique (cms/light_techniques.h, kept in
  // the (cell, technique) pair table), not per cluster.
  bool pairTechniques() const { return pairTechniques_; }
  uint32_t pairCapacity() const { return pairCapacity_; }
  uint32_t emitterCount() const { return emitterCount_; }

  // Counts a vertex whose probe sequence in the cell table was full (shared/cms_cells.h
  // findOrInsertCell, on grid()): it uses no control variate and adds no statistics.
  void countVertexWithoutCell() { verticesWithoutCell_.fetch_add(1, std::memory_order_relaxed); }

  // Whether the vertices of the current sample pass add to the statistics (set per pass from the
  // training schedule, cms/training_schedule.h).
  void setGathering(bool gathers) { passGathers_ = gathers; }
  // ... and whether `cell` still gathers: below shared::kCellSampleCap vertices since its reset
  // (shared::kPairCellSampleCap with the per-technique control variate).
  bool gathering(uint32_t cell) const {
    return passGathers_ && cellSamples_[cell].load(std::memory_order_relaxed) < cellSampleCap_;
  }
  // The statistics weight of a sample of a vertex in `cell` with path throughput `throughput` in
  // `pixel` (docs/estimator.md §5): shared/cms_layouts.h relativeSampleWeight, 1 without relative
  // weighting; 0 for no cell or while the cell does not gather.
  double statisticsWeight(uint32_t cell, glm::vec3 throughput, uint32_t pixel) const;
  void countVertex(uint32_t cell) { cellSamples_[cell].fetch_add(1, std::memory_order_relaxed); }

  // Between sample passes: solves every cell (cms/reference_solve.h), which keeps a cell's
  // selection and statistics unless it adopts a new selection (shared/cms_solve.h).
  void solveAll();
  // Between sample passes: the pixel estimate (shared/pixel_estimate.h) from the running means.
  void refreshPixelEstimate(const std::vector<glm::vec3>& filmMean, uint32_t width, uint32_t height);

  uint64_t cellsUsed() const;
  uint64_t verticesWithoutCell() const { return verticesWithoutCell_.load(); }
  // The pair table's report for the stats JSON (RenderCounters' cvTechniques ... pairBufferBytes).
  void reportPairs(RenderCounters& counters) const;

  // For the accessor macros of the shared headers (cpu/cpu_kernel_access.h). addStatistic adds one
  // term of shared/cms_vertex_terms.h to a cell (a compare-exchange loop: workers add at once).
  void addStatistic(uint32_t cell, uint32_t index, double value);
  uint64_t keyLoad(uint32_t slot) const { return keys_[slot].load(std::memory_order_acquire); }
  uint64_t keyCompareSwap(uint32_t slot, uint64_t expected, uint64_t desired) {
    keys_[slot].compare_exchange_strong(expected, desired, std::memory_order_acq_rel);
    return expected;   // the previous key, as GLSL's atomicCompSwap returns it
  }
  float solution(uint32_t i) const { return solution_[i]; }
  float clusterDefault(uint32_t k) const { return defaults_[k]; }
  const shared::ClusterGpu& cluster(uint32_t k) const { return clusters_[k]; }
  const shared::ClusterLightGpu& clusterLight(uint32_t i) const { return clusterLights_[i]; }
  // The pair table's accessors (shared/cms_pair_terms.h), as the GPU binds them to PAIR_* buffers.
  uint64_t pairKeyLoad(uint32_t slot) const { return pairKeys_[slot].load(std::memory_order_acquire); }
  uint64_t pairKeyCompareSwap(uint32_t slot, uint64_t expected, uint64_t desired) {
    pairKeys_[slot].compare_exchange_strong(expected, desired, std::memory_order_acq_rel);
    return expected;
  }
  const shared::TechniqueRefGpu& technique(uint32_t source) const { return techniques_[source]; }
  float pairAlpha(uint32_t i) const { return pairAlpha_[i]; }
  void addPairStatistic(uint32_t index, double value);
  void pairSlotClaimed(uint32_t slot) { pairOccupied_[pairOccupiedCount_.fetch_add(1, std::memory_order_relaxed)] = slot; }
  uint32_t pairOccupiedCount() const { return pairOccupiedCount_.load(std::memory_order_relaxed); }
  void addPairSample(uint32_t slot) { pairSamples_[slot].fetch_add(1, std::memory_order_relaxed); }
  void countPair(uint32_t counter) { pairCounters_[counter].fetch_add(1, std::memory_order_relaxed); }

 private:
  void solveCell(uint32_t cell);
  void solveCell(uint32_t cell, const shared::SolveParams& params);
  // The per-technique solve sequence between iterations (docs/estimator.md §4): the sparse
  // double-precision solve of every claimed cell, the cluster solve for the selection, and the
  // restart of the pairs whose cell restarted.
  void solvePairs();
  void restartPairs();

  uint32_t L_;
  CellGridSetup grid_;
  bool controlVariate_;
  bool relativeWeighting_;
  bool passGathers_ = true;
  uint32_t cellSampleCap_ = shared::kCellSampleCap;
  shared::SolveParams solveParams_{};
  std::vector<float> defaults_;
  std::vector<shared::ClusterGpu> clusters_;
  std::vector<shared::ClusterLightGpu> clusterLights_;
  std::unique_ptr<std::atomic<uint64_t>[]> keys_;      // 0 = empty slot
  std::unique_ptr<std::atomic<double>[]> stats_;       // cellStatsStride(L) per cell
  std::unique_ptr<std::atomic<uint32_t>[]> cellSamples_;
  std::vector<float> solution_;                        // cellSolutionStride(L) per cell, as on the GPU
  std::vector<glm::vec3> pixelEstimate_;
  std::atomic<uint64_t> verticesWithoutCell_{0};

  // The per-technique control variate (empty unless pairTechniques_).
  bool pairTechniques_ = false;
  uint32_t techniqueCount_ = 0;
  bool techniquesMerged_ = false;
  uint32_t emitterCount_ = 0;
  uint32_t pairCapacity_ = 0;
  std::vector<shared::TechniqueRefGpu> techniques_;     // per technique source
  std::vector<shared::TechniqueClusterGpu> techniqueClusters_;   // per technique (the solve's remainder masses)
  std::unique_ptr<std::atomic<uint64_t>[]> pairKeys_;   // 0 = empty slot; never freed
  std::unique_ptr<std::atomic<double>[]> pairStats_;    // kPairStatsStride per slot
  std::unique_ptr<std::atomic<uint32_t>[]> pairSamples_;
  std::vector<float> pairAlpha_;                        // kPairAlphaStride per slot
  // The claimed slots, in the order they were claimed (shared/cms_pair_state.h PAIR_OCCUPIED): the
  // solve and the restart walk these, not the whole table. Written by the render's threads,
  // read between iterations after they joined.
  std::unique_ptr<uint32_t[]> pairOccupied_;
  std::atomic<uint32_t> pairOccupiedCount_{0};
  std::vector<uint32_t> occupiedSlotsInOrder() const;   // the list, sorted by slot
  std::atomic<uint64_t> pairCounters_[shared::kPairCounterSlots];
};

}  // namespace mixtrace
