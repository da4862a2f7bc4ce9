// The learning methods' training schedule (cms/training_schedule.h): solves at the ends of
// iterations of doubling length, only where an iteration at least as long follows, and samples
// gather statistics only when a solve reads them.
#include <gtest/gtest.h>

#include <vector>

#include "cms/training_schedule.h"

namespace mixtrace {
namespace {

std::vector<uint32_t> solvesUpTo(const TrainingSchedule& s, uint32_t n) {
  std::vector<uint32_t> out;
  for (uint32_t done = 0; done <= n; ++done)
    if (s.solvesAfter(done)) out.push_back(done);
  return out;
}

TEST(TrainingSchedule, OpenEndedSolvesAtEveryBoundaryAndAlwaysGathers) {
  TrainingSchedule s;
  EXPECT_EQ(solvesUpTo(s, 200), (std::vector<uint32_t>{1, 3, 7, 15, 31, 63, 127}));
  for (uint32_t i = 0; i < 300; ++i) EXPECT_TRUE(s.gathers(i)) << i;
}

TEST(TrainingSchedule, ThePlannedLastIterationRunsToTheEndAndGathersNothing) {
  TrainingSchedule s;
  s.plan(64);
  // 63 would serve one sample: the iteration that starts at 31 runs to 64.
  EXPECT_EQ(solvesUpTo(s, 64), (std::vector<uint32_t>{1, 3, 7, 15, 31}));
  for (uint32_t i = 0; i < 31; ++i) EXPECT_TRUE(s.gathers(i)) << i;
  for (uint32_t i = 31; i < 64; ++i) EXPECT_FALSE(s.gathers(i)) << i;
  s.plan(63);   // the iteration from 31 to 63 fits exactly
  EXPECT_EQ(solvesUpTo(s, 63), (std::vector<uint32_t>{1, 3, 7, 15, 31}));
  s.plan(62);   // ... and now it does not
  EXPECT_EQ(solvesUpTo(s, 62), (std::vector<uint32_t>{1, 3, 7, 15}));
  EXPECT_TRUE(s.gathers(14));
  EXPECT_FALSE(s.gathers(15));
}

TEST(TrainingSchedule, ShortRendersLearnLittleOrNothing) {
  TrainingSchedule s;
  s.plan(2);
  EXPECT_TRUE(solvesUpTo(s, 2).empty());
  EXPECT_FALSE(s.gathers(0));
  EXPECT_FALSE(s.gathers(1));
  s.plan(3);
  EXPECT_EQ(solvesUpTo(s, 3), (std::vector<uint32_t>{1}));
  EXPECT_TRUE(s.gathers(0));
  EXPECT_FALSE(s.gathers(1));
}

TEST(TrainingSchedule, HugePlansDoNotOverflow) {
  TrainingSchedule s;
  s.plan(UINT32_MAX);
  EXPECT_TRUE(s.solvesAfter((1u << 31) - 1));
  EXPECT_FALSE(s.solvesAfter(UINT32_MAX));
  EXPECT_TRUE(s.gathers(1u << 30));
  EXPECT_FALSE(s.gathers((1u << 31) - 1));   // its iteration would end past 2^32 samples
}

// --training paper (Hua et al. 2023): statistics from the first 16 samples, one solve after them;
// with relative weighting the first sample only makes the pixel estimate (its solve reads nothing).
TEST(TrainingSchedule, ThePapersScheduleSolvesOnceAfterItsTrainingSamples) {
  TrainingSchedule s;
  s.solveOnceAfter(kPaperTrainingSamples);
  s.plan(128);
  EXPECT_EQ(solvesUpTo(s, 128), (std::vector<uint32_t>{16}));
  for (uint32_t i = 0; i < 16; ++i) EXPECT_TRUE(s.gathers(i)) << i;
  for (uint32_t i = 16; i < 128; ++i) EXPECT_FALSE(s.gathers(i)) << i;

  s.skipFirstSample(true);
  EXPECT_EQ(solvesUpTo(s, 128), (std::vector<uint32_t>{1, 16}));
  EXPECT_FALSE(s.gathers(0));
  for (uint32_t i = 1; i < 16; ++i) EXPECT_TRUE(s.gathers(i)) << i;
  EXPECT_FALSE(s.gathers(16));

  s.plan(16);   // no sample would use the solve: none happens, nothing is gathered
  EXPECT_TRUE(solvesUpTo(s, 16).empty());
  for (uint32_t i = 0; i < 16; ++i) EXPECT_FALSE(s.gathers(i)) << i;
  s.plan(0);    // open-ended: the one solve happens
  EXPECT_EQ(solvesUpTo(s, 200), (std::vector<uint32_t>{1, 16}));
}

}  // namespace
}  // namespace mixtrace
