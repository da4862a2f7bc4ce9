#pragma once
// How a render proceeds, sample pass by sample pass: how many samples per pixel each batch
// renders, what the learning methods are told the total will be, and when it is done. `render`
// runs it to the end (with its progress line and Ctrl-C); the viewer runs one batch per frame.
//
// The rule: one sample first, to measure; then batches sized to take about `batchSeconds` each
// (at most 256 samples), so that the progress line, --time, Ctrl-C and the viewer's input react
// promptly without paying a submission per sample. The learning methods' last training iteration
// gathers no statistics, so they need the total (Renderer::planSamples): a render with a sample
// target plans it at the start; a time-limited one re-estimates it from its pace after every batch.
#include <cstdint>
#include <functional>

#include "backend/renderer.h"

namespace mixtrace {

struct RenderOptions;

// When a render stops. Zero means no limit of that kind; with both, whichever comes first.
struct SampleTarget {
  uint32_t spp = 0;
  double seconds = 0.0;
  double batchSeconds = 0.25;   // about how long one batch should take
  // Tell the renderer the total (see above). The viewer does not: its film restarts whenever the
  // camera moves, and it has always trained open-ended.
  bool planTotal = true;
};

// render's target: --spp and --time, or kDefaultSpp when neither is given.
SampleTarget sampleTargetFor(const RenderOptions& o);

class SampleLoop {
 public:
  // Seconds on some steady clock; the tests pass a fake one.
  using ClockSeconds = std::function<double()>;

  // Plans the renderer's total where the target says so. The renderer must outlive the loop.
  SampleLoop(Renderer& renderer, const SampleTarget& target, ClockSeconds clock = steadySeconds);

  // Renders the next batch; returns false (rendering nothing) once the render is done.
  bool step();
  bool done() const;
  // Done because the time budget is spent (not because the spp target was reached).
  bool outOfTime() const { return outOfTime_; }

  // Seconds spent in step() so far: the render's wall time when the batches follow each other,
  // the rendering share of it in the viewer.
  double seconds() const { return seconds_; }
  // How far along: the share of the time budget where there is one, else of the spp target.
  double fraction() const;
  // The spp target; UINT32_MAX for a time-limited render without one.
  uint32_t targetSpp() const { return targetSpp_; }
  bool timed() const { return target_.seconds > 0.0; }
  // What the loop last told the renderer the total would be (0: open-ended), for the tests.
  uint32_t plannedSamples() const { return planned_; }

  static double steadySeconds();

 private:
  void plan(uint32_t total);

  Renderer* renderer_;
  SampleTarget target_;
  ClockSeconds clock_;
  uint32_t targetSpp_;
  uint32_t batch_ = 1;        // the first batch measures
  double seconds_ = 0.0;
  bool outOfTime_ = false;
  uint32_t planned_ = 0;
};

}  // namespace mixtrace
