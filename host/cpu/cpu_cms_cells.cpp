#include "cpu/cpu_cms_cells.h"

#include <algorithm>
#include <unordered_map>

#include "cms/reference_solve.h"
#include "cms/sparse_solve.h"
#include "cpu/cpu_kernel_access.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_layout.h"


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
  // The per-technique control variate: only for the methods with a control variate, when asked
  // (--cv-techniques triangle) and when the scene has light techniques.
  const LightTechniques& t = cms.techniques;
  pairTechniques_ = controlVariate_ && settings.perTriangleCv && t.techniqueCount > 0;
  for (auto& c : pairCounters_) c.store(0, std::memory_order_relaxed);
  if (pairTechniques_) {
    techniqueCount_ = t.techniqueCount;
    techniquesMerged_ = t.merged();
    emitterCount_ = t.emitterCount;
    techniques_ = t.sources;
    techniqueClusters_ = t.byTechnique;
    // Many more unknowns per cell than clusters: gather on (shared/cms_pair_state.h).
    cellSampleCap_ = shared::kPairCellSampleCap;
    // Room for every (cell, technique) pair, within the largest table (docs/estimator.md §4).
    pairCapacity_ = pairTableCapacity(settings.pairTableSlots, grid_.tableSize, techniqueCount_);
    pairKeys_.reset(new std::atomic<uint64_t>[pairCapacity_]);
    pairStats_.reset(new std::atomic<double>[size_t(pairCapacity_) * shared::kPairStatsStride]);
    pairSamples_.reset(new std::atomic<uint32_t>[pairCapacity_]);
    pairAlpha_.assign(size_t(pairCapacity_) * shared::kPairAlphaStride, 0.0f);   // no coefficients yet
    pairOccupied_.reset(new uint32_t[pairCapacity_]);
    for (uint32_t i = 0; i < pairCapacity_; ++i) {
      pairKeys_[i].store(0, std::memory_order_relaxed);
      pairSamples_[i].store(0, std::memory_order_relaxed);
    }
    for (size_t i = 0; i < size_t(pairCapacity_) * shared::kPairStatsStride; ++i)
      pairStats_[i].store(0.0, std::memory_order_relaxed);
  }
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

void CpuCmsCells::addPairStatistic(uint32_t index, double value) {
  if (value == 0.0) return;
  std::atomic<double>& slot = pairStats_[index];
  double seen = slot.load(std::memory_order_relaxed);
  while (!slot.compare_exchange_weak(seen, seen + value, std::memory_order_relaxed)) {
  }
}

void CpuCmsCells::solveCell(uint32_t cell) { solveCell(cell, solveParams_); }

void CpuCmsCells::solveCell(uint32_t cell, const shared::SolveParams& params) {
  const uint32_t statsStride = shared::cellStatsStride(L_);
  std::atomic<double>* stats = &stats_[size_t(cell) * statsStride];
  std::vector<double> snapshot(statsStride);
  for (uint32_t i = 0; i < statsStride; ++i) snapshot[i] = stats[i].load(std::memory_order_relaxed);
  float* out = &solution_[size_t(cell) * shared::cellSolutionStride(L_)];
  CellSolution s = solveCellReference(snapshot.data(), cellSamples_[cell].load(std::memory_order_relaxed), L_,
                                      params, defaults_.data(), out + shared::solutionSelect(L_, 0));
  for (uint32_t k = 0; k < L_; ++k) {
    for (uint32_t c = 0; c < 3; ++c) out[shared::solutionAlpha(L_, k, c)] = float(s.alpha[k][c]);
    out[shared::solutionSelect(L_, k)] = float(s.select[k]);
  }
  if (!s.keepControlVariate) {   // else the sparse solve's (solvePairs)
    for (uint32_t c = 0; c < 3; ++c) {
      out[shared::solutionAlphaB(L_, c)] = float(s.alphaB[c]);
      out[shared::solutionAlphaSum(L_, c)] = float(s.alphaSum[c]);
    }
    out[shared::solutionValid(L_)] = s.valid ? 1.0f : 0.0f;
  }
  if (s.resetStatistics) {
    for (uint32_t i = 0; i < statsStride; ++i) stats[i].store(0.0, std::memory_order_relaxed);
    cellSamples_[cell].store(0, std::memory_order_relaxed);
  }
}

void CpuCmsCells::solveAll() {
  if (pairTechniques_) {
    solvePairs();
    return;
  }
  // A slot no vertex claimed holds empty statistics and, since the first solve, the defaults; its
  // solve would change nothing, so only claimed cells are solved.
  for (uint32_t cell = 0; cell < grid_.tableSize; ++cell)
    if (keys_[cell].load(std::memory_order_relaxed) != 0) solveCell(cell);
}

void CpuCmsCells::solvePairs() {
  // 1. The sparse solve (cms/sparse_solve.h) of every claimed cell from its A_BB, b_B, sample
  //    count and its pairs: alpha_t per pair, and the cell's alpha_B, validity and sum of alpha.
  std::unordered_map<uint32_t, std::vector<uint32_t>> slotsOfCell;
  for (uint32_t slot : occupiedSlotsInOrder())
    slotsOfCell[shared::pairKeyCell(pairKeys_[slot].load(std::memory_order_relaxed))].push_back(slot);
  SparseSolveParams params;
  params.minCellSamples = solveParams_.minSamples;
  params.ridge = double(solveParams_.ridge);
  params.minTechniqueSamples = shared::kPairMinSamples;
  const uint32_t statsStride = shared::cellStatsStride(L_);
  const uint32_t solutionStride = shared::cellSolutionStride(L_);
  shared::SolveParams keepControlVariate = solveParams_;
  keepControlVariate.flags |= shared::kSolveKeepControlVariate;
  for (uint32_t cell = 0; cell < grid_.tableSize; ++cell) {
    if (keys_[cell].load(std::memory_order_relaxed) == 0) continue;
    const std::atomic<double>* stats = &stats_[size_t(cell) * statsStride];
    SparseCellStatistics statistics;
    statistics.totals.aBB = stats[shared::statsABB(L_)].load(std::memory_order_relaxed);
    for (uint32_t c = 0; c < 3; ++c) statistics.totals.bB[c] = stats[shared::statsBB(L_, c)].load(std::memory_order_relaxed);
    statistics.totals.samples = cellSamples_[cell].load(std::memory_order_relaxed);
    const std::vector<uint32_t>* slots = nullptr;
    if (auto it = slotsOfCell.find(cell); it != slotsOfCell.end()) slots = &it->second;
    if (slots)
      for (uint32_t slot : *slots) {
        SparsePairStatistics pair;
        pair.technique = shared::pairKeyTechnique(pairKeys_[slot].load(std::memory_order_relaxed));
        if (!shared::isRemainderTechnique(pair.technique)) {
          pair.cluster = techniqueClusters_[pair.technique].cluster;
          pair.share = double(techniqueClusters_[pair.technique].share);
        }
        pair.aTT = pairStats_[shared::pairStatsAtt(slot)].load(std::memory_order_relaxed);
        pair.aTB = pairStats_[shared::pairStatsAtB(slot)].load(std::memory_order_relaxed);
        for (uint32_t c = 0; c < 3; ++c) pair.bT[c] = pairStats_[shared::pairStatsBt(slot, c)].load(std::memory_order_relaxed);
        pair.samples = pairSamples_[slot].load(std::memory_order_relaxed);
        statistics.pairs.push_back(pair);
      }
    const SparseCellSolution s = solveSparseCell(statistics, params);
    for (size_t i = 0; slots && i < slots->size(); ++i) {
      for (uint32_t c = 0; c < 3; ++c)
        pairAlpha_[shared::pairAlphaIndex((*slots)[i], c)] = s.valid ? float(s.alpha[i][c]) : 0.0f;
      // Solved: its alpha_t p_t applies (else its cluster's remainder; shared/cms_pair_terms.h).
      pairAlpha_[shared::pairSolvedIndex((*slots)[i])] = s.valid && s.inSystem[i] ? 1.0f : 0.0f;
    }
    float* out = &solution_[size_t(cell) * solutionStride];
    for (uint32_t c = 0; c < 3; ++c) {
      out[shared::solutionAlphaB(L_, c)] = s.valid ? float(s.alphaB[c]) : 0.0f;
      out[shared::solutionAlphaSum(L_, c)] = s.valid ? float(s.alphaSum[c]) : 0.0f;
    }
    out[shared::solutionValid(L_)] = s.valid ? 1.0f : 0.0f;
    // 2. The cluster solve: the selection c_k and its restarts as with per-cluster coefficients,
    //    leaving the control variate of step 1 as it is (kSolveKeepControlVariate).
    solveCell(cell, keepControlVariate);
  }
  // 3. Pairs of restarted cells restart too.
  restartPairs();
}

std::vector<uint32_t> CpuCmsCells::occupiedSlotsInOrder() const {
  // In slot order, as a scan of the table visits them: a cell's pairs reach the double solve in
  // an order that does not depend on which thread claimed a slot first (deterministic sums).
  std::vector<uint32_t> slots(pairOccupied_.get(), pairOccupied_.get() + pairOccupiedCount_.load());
  std::sort(slots.begin(), slots.end());
  return slots;
}

void CpuCmsCells::restartPairs() {
  const uint32_t occupied = pairOccupiedCount_.load();
  for (uint32_t i = 0; i < occupied; ++i) {
    const uint32_t slot = pairOccupied_[i];
    const uint64_t key = pairKeys_[slot].load(std::memory_order_relaxed);
    if (cellSamples_[shared::pairKeyCell(key)].load(std::memory_order_relaxed) != 0) continue;
    for (uint32_t i = 0; i < shared::kPairStatsStride; ++i)
      pairStats_[size_t(slot) * shared::kPairStatsStride + i].store(0.0, std::memory_order_relaxed);
    pairSamples_[slot].store(0, std::memory_order_relaxed);
  }
}

void CpuCmsCells::reportPairs(RenderCounters& counters) const {
  if (!controlVariate_) return;
  counters.cvTechniques = pairTechniques_ ? "triangle" : "cluster";
  counters.techniques = pairTechniques_ ? techniqueCount_ : L_;
  counters.techniquesMerged = techniquesMerged_;
  if (!pairTechniques_) return;
  counters.pairTableCapacity = pairCapacity_;
  counters.pairsUsed = pairOccupiedCount_.load();
  counters.pairSamples = pairCounters_[shared::kPairCounterPairSamples].load();
  counters.pairRefusedSamples = pairCounters_[shared::kPairCounterRefusedSamples].load();
  counters.pairRemainderSamples = pairCounters_[shared::kPairCounterRemainderSamples].load();
  // As the GPU lays them out (shared/cms_pair_layout.h), plus alpha: the CPU's statistics are doubles.
  counters.pairBufferBytes = uint64_t(pairCapacity_) * (shared::kPairKeyBytes + 8u * shared::kPairStatsStride +
                                                        shared::kPairCountBytes + 4u * shared::kPairAlphaStride +
                                                        4u /* the occupied list */);
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
