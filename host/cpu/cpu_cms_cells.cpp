#include "cpu/cpu_cms_cells.h"

#include "cms/reference_solve.h"
#include "cpu/cpu_kernel_access.h"
#include "shared/cms_layouts.h"


namespace mixtrace {

CpuCmsCells::CpuCmsCells(const CmsScene& cms, const Bounds& sceneBounds, const RenderSettings& settings,
                         uint32_t pixelCount)
    : L_(uint32_t(cms.clusters.clusters.size())),
      grid_(makeCellGrid(sceneBounds, settings.cells, L_)),
      controlVariate_(settings.cms.controlVariate),
      relativeWeighting_(settings.relativeWeighting),
      defaults_(cms.clusters.defaultSelection),
      clusters_(cms.clusters.clusters),
      clusterLights_(cms.clusterLights),
      keys_(new std::atomic<uint64_t>[grid_.tableSize]),
      stats_(new std::atomic<double>[size_t(grid_.tableSize) * shared::cellStatsStride(L_)]),
      cellSamples_(new std::atomic<uint32_t>[grid_.tableSize]),
      solution_(size_t(grid_.tableSize) * shared::cellSolutionStride(L_), 0.0f),   // no selection yet
      pixelEstimate_(pixelCount, glm::vec3(0.0f)) {
  for (uint32_t i = 0; i < grid_.tableSize; ++i) {
    keys_[i].store(0, std::memory_order_relaxed);
    cellSamples_[i].store(0, std::memory_order_relaxed);
  }
  for (size_t i = 0; i < size_t(grid_.tableSize) * shared::cellStatsStride(L_); ++i)
    stats_[i].store(0.0, std::memory_order_relaxed);
  // The solve pass's parameters, as the Vulkan renderer sets them (recordSolve).
  solveParams_ = solveParamsFor(settings, grid_.tableSize, L_);
  // Every slot is solved once, so every cell, claimed later or not, starts with the defaults.
  for (uint32_t cell = 0; cell < grid_.tableSize; ++cell) solveCell(cell);
}

double CpuCmsCells::statisticsWeight(uint32_t cell, glm::vec3 throughput, uint32_t pixel) const {
  if (cell == shared::kNoCell || !gathering(cell)) return 0.0;
  return relativeWeighting_ ? double(shared::relativeSampleWeight(throughput, pixelEstimate_[pixel])) : 1.0;
}

void CpuCmsCells::addStatistic(uint32_t cell, uint32_t index, double value) {
  if (value == 0.0) return;
  std::atomic<double>& slot = stats_[size_t(cell) * shared::cellStatsStride(L_) + index];
  double seen = slot.load(std::memory_order_relaxed);
  while (!slot.compare_exchange_weak(seen, seen + value, std::memory_order_relaxed)) {
  }
}

void CpuCmsCells::solveCell(uint32_t cell) {
  const uint32_t statsStride = shared::cellStatsStride(L_);
  std::atomic<double>* stats = &stats_[size_t(cell) * statsStride];
  std::vector<double> snapshot(statsStride);
  for (uint32_t i = 0; i < statsStride; ++i) snapshot[i] = stats[i].load(std::memory_order_relaxed);
  float* out = &solution_[size_t(cell) * shared::cellSolutionStride(L_)];
  CellSolution s = solveCellReference(snapshot.data(), cellSamples_[cell].load(std::memory_order_relaxed), L_,
                                      solveParams_, defaults_.data(), out + shared::solutionSelect(L_, 0));
  for (uint32_t k = 0; k < L_; ++k) {
    for (uint32_t c = 0; c < 3; ++c) out[shared::solutionAlpha(L_, k, c)] = float(s.alpha[k][c]);
    out[shared::solutionSelect(L_, k)] = float(s.select[k]);
  }
  for (uint32_t c = 0; c < 3; ++c) {
    out[shared::solutionAlphaB(L_, c)] = float(s.alphaB[c]);
    out[shared::solutionAlphaSum(L_, c)] = float(s.alphaSum[c]);
  }
  out[shared::solutionValid(L_)] = s.valid ? 1.0f : 0.0f;
  if (s.resetStatistics) {
    for (uint32_t i = 0; i < statsStride; ++i) stats[i].store(0.0, std::memory_order_relaxed);
    cellSamples_[cell].store(0, std::memory_order_relaxed);
  }
}

void CpuCmsCells::solveAll() {
  // A slot no vertex claimed holds empty statistics and, since the first solve, the defaults; its
  // solve would change nothing, so only claimed cells are solved.
  for (uint32_t cell = 0; cell < grid_.tableSize; ++cell)
    if (keys_[cell].load(std::memory_order_relaxed) != 0) solveCell(cell);
}

void CpuCmsCells::refreshPixelEstimate(const std::vector<glm::vec3>& filmMean, uint32_t width, uint32_t height) {
  // shared/pixel_estimate.h reads the means through FILM_MEAN, bound to this thread's context.
  CpuKernelContext context;
  context.filmMean = filmMean.data();
  CpuKernelBinding bind(context);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      pixelEstimate_[size_t(y) * width + x] = shared::pixelEstimateAt(int(x), int(y), int(width), int(height));
}

uint64_t CpuCmsCells::cellsUsed() const {
  uint64_t used = 0;
  for (uint32_t i = 0; i < grid_.tableSize; ++i) used += keys_[i].load(std::memory_order_relaxed) != 0;
  return used;
}

}  // namespace mixtrace
