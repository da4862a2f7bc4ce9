#include "session/sample_loop.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "session/options.h"

namespace mixtrace {

SampleTarget sampleTargetFor(const RenderOptions& o) {
  SampleTarget target;
  target.seconds = o.timeSeconds > 0.0 ? o.timeSeconds : 0.0;
  target.spp = o.spp > 0 ? uint32_t(o.spp) : target.seconds > 0.0 ? 0u : uint32_t(kDefaultSpp);
  return target;
}

double SampleLoop::steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SampleLoop::SampleLoop(Renderer& renderer, const SampleTarget& target, ClockSeconds clock)
    : renderer_(&renderer),
      target_(target),
      clock_(std::move(clock)),
      targetSpp_(target.spp > 0 ? target.spp : UINT32_MAX) {
  // A time-limited render starts open-ended, until its pace gives an estimate.
  if (target_.planTotal) plan(timed() ? 0 : targetSpp_);
}

void SampleLoop::plan(uint32_t total) {
  planned_ = total;
  renderer_->planSamples(total);
}

bool SampleLoop::done() const { return outOfTime_ || renderer_->samplesPerPixel() >= targetSpp_; }

double SampleLoop::fraction() const {
  return timed() ? seconds_ / target_.seconds : double(renderer_->samplesPerPixel()) / targetSpp_;
}

bool SampleLoop::step() {
  if (done()) return false;
  const double start = clock_();
  renderer_->renderSamples(std::min(batch_, targetSpp_ - renderer_->samplesPerPixel()));
  seconds_ += clock_() - start;
  if (timed() && seconds_ >= target_.seconds) {
    outOfTime_ = true;
    return true;
  }
  const double perSample = seconds_ / renderer_->samplesPerPixel();
  if (timed() && target_.planTotal)
    plan(uint32_t(std::min(double(targetSpp_), std::clamp(target_.seconds / perSample, 1.0, 1e9))));
  const double budget = timed() ? std::min(target_.batchSeconds, target_.seconds - seconds_) : target_.batchSeconds;
  batch_ = uint32_t(std::clamp(budget / std::max(perSample, 1e-6), 1.0, 256.0));
  return true;
}

}  // namespace mixtrace
