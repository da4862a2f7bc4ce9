#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a render: the first one asks the render to stop after the
// sample pass in flight, so that what has been rendered is written; a second one ends the process
// at once (the signal's default action). Exit status after a requested stop: 128 + the signal's
// number (130 for SIGINT), the shell's convention for "killed by that signal".
#include <string>

namespace mixtrace {

class StopOnSignal {
 public:
  // `announce`: the first signal prints one line saying what happens (from the handler).
  explicit StopOnSignal(bool announce);
  ~StopOnSignal();   // the previous handlers again
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  bool requested() const;
  std::string signalName() const;   // "SIGINT", "SIGTERM"; "" before any
  int exitCode() const;             // 128 + signal number; 0 before any
};

}  // namespace mixtrace
