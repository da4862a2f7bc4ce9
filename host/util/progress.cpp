#include "util/progress.h"

#include <unistd.h>

namespace mixtrace {

Progress::Progress(bool enabled) : Progress(enabled, stderr, isatty(STDERR_FILENO) != 0, kLogIntervalSeconds) {}

Progress::Progress(bool enabled, std::FILE* out, bool terminal, double intervalSeconds)
    : out_(out),
      enabled_(enabled),
      terminal_(terminal),
      intervalSeconds_(intervalSeconds),
      start_(std::chrono::steady_clock::now()) {}

void Progress::update(double fraction, const std::string& text) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (terminal_ ? elapsed < kTerminalDelaySeconds : elapsed - lastLineSeconds_ < intervalSeconds_) return;
  char eta[64] = "";
  if (fraction > 0.0 && fraction < 1.0) std::snprintf(eta, sizeof(eta), ", ETA %.0f s", elapsed * (1.0 - fraction) / fraction);
  std::fprintf(out_, "%smixtrace: %5.1f%%  %s, %.1f s%s%s", terminal_ ? "\r\033[K" : "",
               fraction >= 0.0 ? 100.0 * fraction : 0.0, text.c_str(), elapsed, eta, terminal_ ? "" : "\n");
  std::fflush(out_);
  lastLineSeconds_ = elapsed;
  shown_ = true;
}

void Progress::finish() {
  if (shown_ && terminal_) std::fprintf(out_, "\n");
  shown_ = false;
}

}  // namespace mixtrace
