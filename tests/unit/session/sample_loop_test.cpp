// The sample loop (session/sample_loop.h) that render and view share: its batch sizes, what it
// tells the learning methods the total will be, and when it stops, with a fake renderer on a fake
// clock (each sample takes a fixed, binary-exact time, so the decisions are exact too).
#include "session/sample_loop.h"

#include <gtest/gtest.h>

#include <vector>

#include "session/options.h"

namespace mixtrace {
namespace {

class FakeRenderer : public Renderer {
 public:
  explicit FakeRenderer(double secondsPerSample, double& clock) : secondsPerSample_(secondsPerSample), clock_(clock) {}
  void renderSamples(uint32_t count) override {
    batches.push_back(count);
    spp_ += count;
    clock_ += count * secondsPerSample_;
  }
  uint32_t samplesPerPixel() const override { return spp_; }
  Image readImage(Image*) const override { return Image{}; }
  AovImages readAovs() const override { return {}; }
  RenderCounters counters() const override { return {}; }
  std::map<std::string, double> passTimesMs() const override { return {}; }
  std::string deviceName() const override { return "fake"; }
  // What the training schedule was told (Renderer::planSamples): whether it solves after `done`.
  bool solvesAfter(uint32_t done) const { return schedule_.solvesAfter(done); }

  std::vector<uint32_t> batches;

 private:
  double secondsPerSample_;
  double& clock_;
  uint32_t spp_ = 0;
};

struct LoopRun {
  std::vector<uint32_t> batches;
  std::vector<uint32_t> plans;   // what the loop had planned after each batch
  uint32_t spp = 0;
  double seconds = 0.0;
};

LoopRun runToTheEnd(const SampleTarget& target, double secondsPerSample) {
  double clock = 100.0;
  FakeRenderer renderer(secondsPerSample, clock);
  SampleLoop loop(renderer, target, [&] { return clock; });
  LoopRun run;
  run.plans.push_back(loop.plannedSamples());
  while (loop.step()) run.plans.push_back(loop.plannedSamples());
  EXPECT_TRUE(loop.done());
  EXPECT_FALSE(loop.step()) << "a finished loop renders nothing more";
  run.batches = renderer.batches;
  run.spp = renderer.samplesPerPixel();
  run.seconds = loop.seconds();
  return run;
}

SampleTarget sppTarget(uint32_t spp) {
  SampleTarget t;
  t.spp = spp;
  return t;
}

TEST(SampleLoop, OneSampleFirstThenBatchesOfAQuarterSecond) {
  // 1/512 s per sample: a quarter second is 128 samples.
  const LoopRun run = runToTheEnd(sppTarget(300), 1.0 / 512);
  EXPECT_EQ(run.batches, (std::vector<uint32_t>{1, 128, 128, 43}));
  EXPECT_EQ(run.spp, 300u);
}

TEST(SampleLoop, StopsAtTheTargetAndPlansIt) {
  const LoopRun run = runToTheEnd(sppTarget(16), 1.0 / 512);
  EXPECT_EQ(run.batches, (std::vector<uint32_t>{1, 15}));
  for (uint32_t planned : run.plans) EXPECT_EQ(planned, 16u);
  // The renderer was told: with 16 planned, the solve after 15 would serve one sample.
  double clock = 0.0;
  FakeRenderer renderer(1.0 / 512, clock);
  SampleLoop loop(renderer, sppTarget(16), [&] { return clock; });
  EXPECT_TRUE(renderer.solvesAfter(7));
  EXPECT_FALSE(renderer.solvesAfter(15));
}

TEST(SampleLoop, BatchesAreAtMost256Samples) {
  const LoopRun run = runToTheEnd(sppTarget(600), 1.0 / 4096);   // a quarter second would be 1024
  EXPECT_EQ(run.batches, (std::vector<uint32_t>{1, 256, 256, 87}));
}

TEST(SampleLoop, ATimeBudgetStopsItAndItsPaceSetsThePlan) {
  SampleTarget target;
  target.seconds = 1.0;
  const LoopRun run = runToTheEnd(target, 1.0 / 512);
  // The last batch is cut to the time left: 127/512 s after 385/512 s.
  EXPECT_EQ(run.batches, (std::vector<uint32_t>{1, 128, 128, 128, 127}));
  EXPECT_DOUBLE_EQ(run.seconds, 1.0);
  // Open-ended until the first batch gives a pace, then 1 s / (1/512 s) = 512.
  EXPECT_EQ(run.plans.front(), 0u);
  for (size_t i = 1; i + 1 < run.plans.size(); ++i) EXPECT_EQ(run.plans[i], 512u) << i;
}

TEST(SampleLoop, WithBothASppTargetAndTimeWhicheverComesFirst) {
  SampleTarget target;
  target.seconds = 10.0;
  target.spp = 100;
  const LoopRun run = runToTheEnd(target, 1.0 / 512);
  EXPECT_EQ(run.spp, 100u);
  EXPECT_EQ(run.plans.back(), 100u) << "the plan never exceeds the spp target";

  target.seconds = 0.5;
  target.spp = 100000;
  EXPECT_EQ(runToTheEnd(target, 1.0 / 512).spp, 256u);
}

TEST(SampleLoop, TheViewerBudgetsAFrameAndPlansNothing) {
  SampleTarget target;
  target.spp = 64;
  target.batchSeconds = 1.0 / 16;
  target.planTotal = false;
  double clock = 0.0;
  FakeRenderer renderer(1.0 / 512, clock);
  SampleLoop loop(renderer, target, [&] { return clock; });
  EXPECT_TRUE(loop.step());
  EXPECT_TRUE(loop.step());
  EXPECT_EQ(renderer.batches, (std::vector<uint32_t>{1, 32}));
  EXPECT_EQ(loop.plannedSamples(), 0u);
  EXPECT_TRUE(renderer.solvesAfter(31)) << "open-ended: every boundary solves";
  EXPECT_DOUBLE_EQ(loop.fraction(), 33.0 / 64);
}

TEST(SampleLoop, RenderTargetFromTheOptions) {
  RenderOptions o;
  EXPECT_EQ(sampleTargetFor(o).spp, uint32_t(kDefaultSpp));
  EXPECT_EQ(sampleTargetFor(o).seconds, 0.0);
  o.timeSeconds = 2.0;
  EXPECT_EQ(sampleTargetFor(o).spp, 0u) << "--time alone has no spp target";
  EXPECT_EQ(sampleTargetFor(o).seconds, 2.0);
  o.spp = 8;
  EXPECT_EQ(sampleTargetFor(o).spp, 8u);
}

}  // namespace
}  // namespace mixtrace
