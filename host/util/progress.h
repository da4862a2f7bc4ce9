#pragma once
// Progress of a render on stderr. On a terminal: one line rewritten in place, shown once the
// render has run for a second (short renders stay quiet). Elsewhere (a CI log, a pipe, a file):
// a plain line every kLogIntervalSeconds, so that a long render shows it is alive without
// filling the log with carriage returns.
#include <chrono>
#include <cstdio>
#include <string>

namespace mixtrace {

class Progress {
 public:
  static constexpr double kTerminalDelaySeconds = 1.0;
  static constexpr double kLogIntervalSeconds = 5.0;

  // To stderr; a terminal or not is decided by isatty.
  explicit Progress(bool enabled);
  // To `out`, as a terminal or as a log with lines `intervalSeconds` apart (tests).
  Progress(bool enabled, std::FILE* out, bool terminal, double intervalSeconds);

  // fraction in [0, 1] or negative when unknown; text: e.g. "12/64 spp, 1.2 M samples/s".
  void update(double fraction, const std::string& text);
  void finish();

 private:
  std::FILE* out_;
  bool enabled_;
  bool terminal_;
  double intervalSeconds_;
  double lastLineSeconds_ = 0.0;   // log mode: when the last plain line was written
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mixtrace
