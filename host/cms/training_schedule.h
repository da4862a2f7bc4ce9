#pragma once
// When the learning methods (learned, cv, cms) solve their cells and which samples gather the
// statistics a solve reads (docs/estimator.md §7). Training runs in iterations of doubling length:
// the cells are solved after samples 1, 3, 7, 15, ... But a solve pays only if an iteration follows
// that is at least as long as the statistics behind it: with 64 planned samples, solving after
// sample 63 would serve one sample. So the last iteration runs from the last useful solve to the
// end, and its samples gather nothing: no solve reads them. That is about half of every render's
// samples, which then pay none of the statistics' cost. Both backends follow this one schedule.
//
// The published method trains once instead (docs/estimator.md §7, --training paper): statistics
// from the first N samples (16 in the paper), one solve, and the rest of the render uses it.
#include <cstdint>

namespace mixtrace {

// The published method's training length (Hua et al. 2023: 16 spp, then one solve).
constexpr uint32_t kPaperTrainingSamples = 16;

class TrainingSchedule {
 public:
  // Samples per pixel the render plans; 0 = open-ended (solve at every boundary, always gather).
  // A time-limited render updates its estimate as it goes.
  void plan(uint32_t totalSamples) { planned_ = totalSamples; }
  // --train-spp: no solve after this many samples (0 = no limit): the paper trains for a fixed
  // budget (16 spp) and then renders with what it learned.
  void limitTraining(uint32_t samples) { trainLimit_ = samples; }
  // With relative weighting the first sample gathers nothing: it makes the pixel estimate the
  // weights divide by (before it, every pixel would look black and every vertex get the largest
  // weight, and those statistics would outweigh all later ones).
  void skipFirstSample(bool skip) { skipFirst_ = skip; }
  // --training paper: one solve, after `samples` samples, reading the statistics of all of them
  // (but the first, with relative weighting: that one's solve only makes the pixel estimate).
  void solveOnceAfter(uint32_t samples) { onceAfter_ = samples; }

  // Whether the cells are solved once `done` samples per pixel are complete.
  bool solvesAfter(uint32_t done) const {
    if (onceAfter_ != 0) {
      const bool serves = planned_ == 0 || planned_ > onceAfter_;   // a sample follows the solve
      return serves && (done == onceAfter_ || (skipFirst_ && done == 1));
    }
    if (done == 0 || ((done + 1) & done) != 0) return false;      // not 2^k - 1
    if (trainLimit_ != 0 && done > trainLimit_) return false;      // training is over
    return planned_ == 0 || uint64_t(done) * 2 + 1 <= planned_;    // the next iteration fits
  }

  // Whether sample pass `index` (0-based) adds to the statistics: only when the solve at the end of
  // its iteration happens.
  bool gathers(uint32_t index) const {
    if (index == 0 && skipFirst_) return false;
    if (onceAfter_ != 0) return index < onceAfter_ && solvesAfter(onceAfter_);
    uint64_t boundary = 1;   // the end of index's iteration: the smallest 2^k - 1 >= index + 1
    while (boundary < uint64_t(index) + 1) boundary = boundary * 2 + 1;
    return boundary > UINT32_MAX || solvesAfter(uint32_t(boundary));
  }

 private:
  uint32_t planned_ = 0;
  uint32_t trainLimit_ = 0;
  uint32_t onceAfter_ = 0;   // 0: iterations of doubling length
  bool skipFirst_ = false;
};

}  // namespace mixtrace
