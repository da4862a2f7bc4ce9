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
// The shared headers reach this state through the macros of cpu/cpu_cms_access.h.
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

  // The cell of a vertex (found or claimed), or shared::kNoCell when its probe sequence is full
  // (counted: such a vertex uses no control variate and adds no statistics).
  uint32_t findCell(glm::vec3 position, glm::vec3 geometricNormal, uint32_t material);

  // Whether the vertices of the current sample pass add to the statistics (set per pass from the
  // training schedule, cms/training_schedule.h).
  void setGathering(bool gathers) { passGathers_ = gathers; }
  // ... and whether `cell` still gathers: below shared::kCellSampleCap vertices since its reset.
  bool gathering(uint32_t cell) const {
    return passGathers_ && cellSamples_[cell].load(std::memory_order_relaxed) < shared::kCellSampleCap;
  }
  // The weight of a sample of a vertex with path throughput `throughput` in `pixel`
  // (docs/estimator.md §5): shared/cms_layouts.h relativeSampleWeight, 1 without relative
  // weighting, 0 while not gathering.
  double sampleWeight(glm::vec3 throughput, uint32_t pixel) const;

  // The statistics of one sample (docs/estimator.md §4), k = shared::kNoCell for a sample in no
  // cluster's support: A_kk += w pk^2 / peff^2, A_kB += w pk pB / peff^2, A_BB += w pB^2 / peff^2
  // and b_k += w f pk / peff^2, b_B += w f pB / peff^2. Computed in double from the float
  // densities.
  void addSampleToA(uint32_t cell, uint32_t k, double pk, double pB, double peff, double w);
  void addSampleToB(uint32_t cell, uint32_t k, glm::vec3 f, double pk, double pB, double peff, double w);
  void countVertex(uint32_t cell) { cellSamples_[cell].fetch_add(1, std::memory_order_relaxed); }

  // Between sample passes: solves every cell (cms/reference_solve.h), which keeps a cell's
  // selection and statistics unless it adopts a new selection (shared/cms_solve.h).
  void solveAll();
  // Between sample passes: the pixel estimate (shared/pixel_estimate.h) from the running means.
  void refreshPixelEstimate(const std::vector<glm::vec3>& filmMean, uint32_t width, uint32_t height);

  uint64_t cellsUsed() const;
  uint64_t verticesWithoutCell() const { return verticesWithoutCell_.load(); }

  // For the accessor macros of the shared headers (cpu/cpu_cms_access.h).
  uint64_t keyLoad(uint32_t slot) const { return keys_[slot].load(std::memory_order_acquire); }
  uint64_t keyCompareSwap(uint32_t slot, uint64_t expected, uint64_t desired) {
    keys_[slot].compare_exchange_strong(expected, desired, std::memory_order_acq_rel);
    return expected;   // the previous key, as GLSL's atomicCompSwap returns it
  }
  float solution(uint32_t i) const { return solution_[i]; }
  float clusterDefault(uint32_t k) const { return defaults_[k]; }
  const shared::ClusterGpu& cluster(uint32_t k) const { return clusters_[k]; }
  const shared::ClusterLightGpu& clusterLight(uint32_t i) const { return clusterLights_[i]; }

 private:
  void solveCell(uint32_t cell);
  void add(uint32_t cell, uint32_t index, double value);

  uint32_t L_;
  CellGridSetup grid_;
  bool controlVariate_;
  bool relativeWeighting_;
  bool passGathers_ = true;
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
};

}  // namespace mixtrace
