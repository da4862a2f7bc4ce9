#pragma once
// The statistics of controlled mixture sampling in the sparse form of one control-variate
// technique per emissive triangle (../shared/cms.md §4, docs/estimator.md §4), in double
// precision, on the host. Not wired into rendering yet: the CPU reference of what the GPU's hashed
// table of (cell, technique) pairs gathers, and the input of host/cms/sparse_solve.h.
//
// A sample z drawn at a vertex of a cell touches at most one light technique t (triangles have
// disjoint supports), so A is an arrowhead matrix and a sample updates only
//     per cell:             A_BB, b_B (RGB), the cell's sample count
//     per (cell, t) pair:   A_tt, A_tB, b_t (RGB), the pair's sample count
// with A_ij += w p_i p_j / p_eff^2 and b_i += w f p_i / p_eff^2. Only pairs that received samples
// are stored: a cell seeing 12 of a scene's 10,000 triangles holds 12 pairs.
//
// The table is bounded (a capacity in entries; a cell's own totals are one entry, each pair one
// more), like the GPU table it mirrors. Nothing is lost silently:
//   - a sample of a cell not in the table when it is full is refused whole (counted);
//   - a sample of a known cell whose (cell, t) pair is new when the table is full adds to the
//     cell's totals and is counted as a refused pair sample. Technique t is then absent from the
//     cell, i.e. its alpha_t is 0, and the cell's totals still hold every sample, so the cell
//     estimates exactly the system restricted to alpha_t = 0 (the optimum for the techniques that
//     remain). A pair is refused when it would be created, and stays refused until its cell
//     restarts (resetCell), even if other cells free entries meanwhile, so all of its samples are.
// Any alpha keeps the estimator unbiased (docs/estimator.md §3), so refusals only cost variance.
// Non-finite inputs are accumulated as given: the solve drops what they spoil (sparse_solve.h).
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/glm.hpp>

namespace mixtrace {

// The technique of a sample that touches no light technique (a BSDF sample that hit nothing
// emissive, or failed).
constexpr uint32_t kNoLightTechnique = 0xffffffffu;

// What one sample contributes: the light technique whose support holds z (or none), its density
// p_t(z) (unweighted by selection), the BSDF density p_B(z), the mixture's p_eff(z), the integrand
// f(z) (RGB) and the vertex's weight w (docs/estimator.md §5).
struct SparseSample {
  uint32_t technique = kNoLightTechnique;
  double pT = 0.0;
  double pB = 0.0;
  double pEff = 1.0;
  glm::dvec3 f{0.0};
  double weight = 1.0;
};

// A cell's row of the BSDF technique.
struct SparseCellTotals {
  double aBB = 0.0;
  glm::dvec3 bB{0.0};
  uint64_t samples = 0;   // every sample of the cell, whatever technique it touched
};

// One (cell, technique) pair. `technique` may be a remainder technique (shared/cms_pair_layout.h
// remainderTechnique): the solve gives it the mass of its cluster's triangles that have no solved
// pair in the cell, from the clusters and shares of the triangle pairs.
struct SparsePairStatistics {
  uint32_t technique = kNoLightTechnique;
  double aTT = 0.0;
  double aTB = 0.0;
  glm::dvec3 bT{0.0};
  uint64_t samples = 0;   // the samples that touched this technique in this cell
  uint32_t cluster = 0;   // a triangle technique's cluster (a remainder's is in its id)
  double share = 1.0;     // a triangle technique's Q_t (unused for a remainder)
};

struct SparseCellStatistics {
  SparseCellTotals totals;
  std::vector<SparsePairStatistics> pairs;   // in order of first sample
  uint64_t refusedPairSamples = 0;           // samples in the totals whose pair did not fit
};

// What add() did with a sample.
enum class SparseAddResult {
  Added,            // cell totals and (if any) pair updated
  PairRefused,      // cell totals updated; the new (cell, technique) pair did not fit
  CellRefused,      // nothing added: the new cell did not fit
};

// Increments of one sample to a cell's totals and a pair (cms.md §4), exposed for the tests and
// for a caller that keeps its own storage. The ratios p/p_eff are formed before squaring: p_eff^2
// may overflow where the ratios are moderate.
void addSampleTo(SparseCellTotals& totals, SparsePairStatistics* pair, const SparseSample& s);

class SparseStatisticsTable {
 public:
  // capacity: entries the table may hold, a cell's totals and each of its pairs one each.
  explicit SparseStatisticsTable(size_t capacity);

  SparseAddResult add(uint32_t cell, const SparseSample& sample);

  // Adds another table's statistics (e.g. one a worker thread gathered alone), with the same
  // capacity rules as add(): a new cell that does not fit is refused with all its samples, a new
  // pair that does not fit (or was refused here before) leaves its samples in its cell's totals
  // only. The other table's refusal counts are added to these; the pairs it refused become
  // refused here too where this table does not hold them yet. A pair it refused that this table
  // does hold misses those samples while its cell's totals keep them (still unbiased, a worse
  // alpha), so give a worker's table at least this table's capacity.
  void merge(const SparseStatisticsTable& other);

  // The cell's statistics, or nullptr when it has none.
  const SparseCellStatistics* cell(uint32_t cell) const;
  const std::unordered_map<uint32_t, SparseCellStatistics>& cells() const { return cells_; }

  // Forgets a cell's statistics and frees its entries (a cell whose selection changed restarts,
  // docs/estimator.md §7).
  void resetCell(uint32_t cell);
  void clear();

  size_t capacity() const { return capacity_; }
  size_t entries() const { return entries_; }
  size_t pairCount() const { return pairIndex_.size(); }
  // Refusals since construction (or clear()): pairs that could not be created (each counted
  // once), samples held in their cell's totals whose pair was refused, samples in no cell.
  uint64_t refusedPairs() const { return refusedPairs_; }
  uint64_t refusedPairSamples() const { return refusedPairSamples_; }
  uint64_t refusedCellSamples() const { return refusedCellSamples_; }

 private:
  static uint64_t key(uint32_t cell, uint32_t technique) { return (uint64_t(cell) << 32) | technique; }

  size_t capacity_;
  size_t entries_ = 0;
  std::unordered_map<uint32_t, SparseCellStatistics> cells_;
  std::unordered_map<uint64_t, uint32_t> pairIndex_;   // (cell, technique) -> index in the cell's pairs
  std::unordered_set<uint64_t> refusedKeys_;   // pairs refused since their cell (re)started
  uint64_t refusedPairs_ = 0;
  uint64_t refusedPairSamples_ = 0;
  uint64_t refusedCellSamples_ = 0;
};

}  // namespace mixtrace
