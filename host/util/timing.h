#pragma once
// Wall-clock helpers the commands share (render's progress line, the viewer's title).
#include <chrono>
#include <cstdio>
#include <string>

namespace mixtrace {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A rate in millions, as "1.23 M".
inline std::string formatRate(double perSecond) {
  char b[32];
  std::snprintf(b, sizeof(b), "%.2f M", perSecond * 1e-6);
  return b;
}

}  // namespace mixtrace
