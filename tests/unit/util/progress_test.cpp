// Progress on stderr (issue 11, point 16): when stderr is not a terminal (CI logs, pipes) a plain
// line every few seconds, without carriage returns or escape codes; on a terminal one line
// rewritten in place; nothing when disabled (-q).
#include "util/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace mixtrace {
namespace {

std::string contentsOf(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  for (int c; (c = std::fgetc(file)) != EOF;) text += char(c);
  return text;
}

// Updates every 10 ms for `seconds`, as a render's batches would.
std::string run(bool enabled, bool terminal, double interval, double seconds) {
  std::FILE* file = std::tmpfile();
  Progress progress(enabled, file, terminal, interval);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (int i = 1; std::chrono::steady_clock::now() < end; ++i) {
    progress.update(0.25, std::to_string(i) + "/64 spp");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  progress.finish();
  const std::string text = contentsOf(file);
  std::fclose(file);
  return text;
}

size_t count(const std::string& text, char c) {
  size_t n = 0;
  for (char t : text) n += t == c;
  return n;
}

TEST(Progress, PlainLinesEveryIntervalWhenNotATerminal) {
  const std::string text = run(true, false, 0.1, 0.55);
  EXPECT_GE(count(text, '\n'), 3u) << text;   // about 5 (at 0.1, 0.2, ... s), fewer on a busy machine
  EXPECT_LE(count(text, '\n'), 6u) << text;
  EXPECT_EQ(count(text, '\r'), 0u) << text;
  EXPECT_EQ(count(text, '\033'), 0u) << text;
  EXPECT_EQ(text.rfind("mixtrace: ", 0), 0u) << text;
  EXPECT_NE(text.find("spp"), std::string::npos);
  EXPECT_NE(text.find("ETA"), std::string::npos);
}

TEST(Progress, TheLogIntervalIsSeconds) {
  EXPECT_GE(Progress::kLogIntervalSeconds, 2.0);
  EXPECT_LE(Progress::kLogIntervalSeconds, 10.0);
}

TEST(Progress, NothingWhenDisabledOrShort) {
  EXPECT_EQ(run(false, false, 0.05, 0.2), "");
  EXPECT_EQ(run(true, false, 10.0, 0.1), "") << "a short render prints no progress line";
  EXPECT_EQ(run(true, true, 0.05, 0.1), "") << "a terminal shows the line from the first second";
}

TEST(Progress, OneLineRewrittenOnATerminal) {
  const std::string text = run(true, true, Progress::kLogIntervalSeconds, Progress::kTerminalDelaySeconds + 0.1);
  EXPECT_GE(count(text, '\r'), 1u) << text;
  EXPECT_EQ(count(text, '\n'), 1u) << "only finish() ends the line: " << text;
}

}  // namespace
}  // namespace mixtrace
