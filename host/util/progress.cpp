#include "util/progress.h"

#include <cstdio>
#include <unistd.h>

namespace mixtrace {

Progress::Progress(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

void Progress::update(double fraction, const std::string& text) {
  if (!enabled_) return;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < 1.0) return;
  char eta[64] = "";
  if (fraction > 0.0 && fraction < 1.0) std::snprintf(eta, sizeof(eta), ", ETA %.0f s", elapsed * (1.0 - fraction) / fraction);
  std::fprintf(stderr, "\r\033[Kmixtrace: %5.1f%%  %s, %.1f s%s", fraction >= 0.0 ? 100.0 * fraction : 0.0, text.c_str(), elapsed, eta);
  std::fflush(stderr);
  shown_ = true;
}

void Progress::finish() {
  if (shown_) std::fprintf(stderr, "\n");
  shown_ = false;
}

}  // namespace mixtrace
