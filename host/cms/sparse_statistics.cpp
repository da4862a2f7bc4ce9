#include "cms/sparse_statistics.h"

#include <iterator>

namespace mixtrace {

void addSampleTo(SparseCellTotals& totals, SparsePairStatistics* pair, const SparseSample& s) {
  const double rB = s.pB / s.pEff;
  totals.aBB += s.weight * rB * rB;
  totals.bB += (s.weight * rB / s.pEff) * s.f;
  totals.samples += 1;
  if (pair == nullptr) return;
  const double rT = s.pT / s.pEff;
  pair->aTT += s.weight * rT * rT;
  pair->aTB += s.weight * rT * rB;
  pair->bT += (s.weight * rT / s.pEff) * s.f;
  pair->samples += 1;
}

SparseStatisticsTable::SparseStatisticsTable(size_t capacity) : capacity_(capacity) {}

SparseAddResult SparseStatisticsTable::add(uint32_t cellId, const SparseSample& sample) {
  auto found = cells_.find(cellId);
  if (found == cells_.end()) {
    if (entries_ >= capacity_) {
      refusedCellSamples_ += 1;
      return SparseAddResult::CellRefused;
    }
    found = cells_.emplace(cellId, SparseCellStatistics{}).first;
    entries_ += 1;
  }
  SparseCellStatistics& cell = found->second;
  if (sample.technique == kNoLightTechnique) {
    addSampleTo(cell.totals, nullptr, sample);
    return SparseAddResult::Added;
  }
  const uint64_t k = key(cellId, sample.technique);
  auto slot = pairIndex_.find(k);
  if (slot == pairIndex_.end()) {
    // A pair refused once stays refused until its cell restarts, even if entries free up
    // meanwhile: created later, it would miss the samples its cell's totals already hold.
    if (entries_ >= capacity_ || refusedKeys_.count(k) != 0) {
      if (refusedKeys_.insert(k).second) refusedPairs_ += 1;
      refusedPairSamples_ += 1;
      cell.refusedPairSamples += 1;
      addSampleTo(cell.totals, nullptr, sample);   // the cell keeps every sample (header comment)
      return SparseAddResult::PairRefused;
    }
    slot = pairIndex_.emplace(k, uint32_t(cell.pairs.size())).first;
    SparsePairStatistics pair;
    pair.technique = sample.technique;
    cell.pairs.push_back(pair);
    entries_ += 1;
  }
  addSampleTo(cell.totals, &cell.pairs[slot->second], sample);
  return SparseAddResult::Added;
}

void SparseStatisticsTable::merge(const SparseStatisticsTable& other) {
  for (const auto& [cellId, from] : other.cells_) {
    auto found = cells_.find(cellId);
    if (found == cells_.end()) {
      if (entries_ >= capacity_) {
        refusedCellSamples_ += from.totals.samples;
        continue;
      }
      found = cells_.emplace(cellId, SparseCellStatistics{}).first;
      entries_ += 1;
    }
    SparseCellStatistics& cell = found->second;
    cell.totals.aBB += from.totals.aBB;
    cell.totals.bB += from.totals.bB;
    cell.totals.samples += from.totals.samples;
    cell.refusedPairSamples += from.refusedPairSamples;
    refusedPairSamples_ += from.refusedPairSamples;
    for (const SparsePairStatistics& pair : from.pairs) {
      const uint64_t k = key(cellId, pair.technique);
      auto slot = pairIndex_.find(k);
      if (slot == pairIndex_.end()) {
        if (entries_ >= capacity_ || refusedKeys_.count(k) != 0) {
          if (refusedKeys_.insert(k).second) refusedPairs_ += 1;
          refusedPairSamples_ += pair.samples;
          cell.refusedPairSamples += pair.samples;
          continue;
        }
        slot = pairIndex_.emplace(k, uint32_t(cell.pairs.size())).first;
        SparsePairStatistics fresh;
        fresh.technique = pair.technique;
        cell.pairs.push_back(fresh);
        entries_ += 1;
      }
      SparsePairStatistics& into = cell.pairs[slot->second];
      into.aTT += pair.aTT;
      into.aTB += pair.aTB;
      into.bT += pair.bT;
      into.samples += pair.samples;
    }
  }
  for (uint64_t k : other.refusedKeys_)
    if (pairIndex_.count(k) == 0 && cells_.count(uint32_t(k >> 32)) != 0 && refusedKeys_.insert(k).second)
      refusedPairs_ += 1;
  refusedCellSamples_ += other.refusedCellSamples_;   // never entered the other table's cells
}

const SparseCellStatistics* SparseStatisticsTable::cell(uint32_t cellId) const {
  auto found = cells_.find(cellId);
  return found == cells_.end() ? nullptr : &found->second;
}

void SparseStatisticsTable::resetCell(uint32_t cellId) {
  auto found = cells_.find(cellId);
  if (found == cells_.end()) return;
  for (const SparsePairStatistics& pair : found->second.pairs) pairIndex_.erase(key(cellId, pair.technique));
  entries_ -= found->second.pairs.size() + 1;
  cells_.erase(found);
  // A pair refused before may fit now: forget that it was refused, so it counts again if it is.
  for (auto it = refusedKeys_.begin(); it != refusedKeys_.end();)
    it = (*it >> 32) == cellId ? refusedKeys_.erase(it) : std::next(it);
}

void SparseStatisticsTable::clear() {
  cells_.clear();
  pairIndex_.clear();
  refusedKeys_.clear();
  entries_ = 0;
  refusedPairs_ = refusedPairSamples_ = refusedCellSamples_ = 0;
}

}  // namespace mixtrace
