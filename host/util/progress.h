#pragma once
// A one-line progress report on a terminal (stderr), shown only once a render has run for a
// second, so short renders and non-interactive runs (tests, CI, pipes) stay quiet.
#include <chrono>
#include <string>

namespace mixtrace {

class Progress {
 public:
  explicit Progress(bool enabled);
  // fraction in [0, 1] or negative when unknown; text: e.g. "12/64 spp, 1.2 M samples/s".
  void update(double fraction, const std::string& text);
  void finish();

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mixtrace
