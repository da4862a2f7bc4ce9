#include "app/stop_on_signal.h"

#include <csignal>
#include <cstring>

#include <unistd.h>

namespace mixtrace {
namespace {

// What the handler may touch: a signal handler can only safely store to a sig_atomic_t and call
// async-signal-safe functions (write, signal, raise).
volatile std::sig_atomic_t gSignal = 0;
bool gAnnounce = false;
char gMessage[160] = "";
struct sigaction gPrevious[2];
constexpr int kSignals[2] = {SIGINT, SIGTERM};

extern "C" void onStopSignal(int signal) {
  if (gSignal != 0) {   // the second one: stop now, as if no handler were installed
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  gSignal = signal;
  if (gAnnounce) {
    const ssize_t ignored = ::write(STDERR_FILENO, gMessage, std::strlen(gMessage));
    (void)ignored;
  }
}

}  // namespace

StopOnSignal::StopOnSignal(bool announce) {
  gSignal = 0;
  gAnnounce = announce;
  // On a terminal the progress line is being rewritten in place: clear it first.
  std::strcpy(gMessage, ::isatty(STDERR_FILENO) ? "\r\033[K" : "");
  std::strcat(gMessage,
              "mixtrace: stopping after the sample pass in flight, then writing what has been rendered "
              "(send the signal again to abort at once)\n");
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;   // a wait for the device resumes rather than failing with EINTR
  for (int i = 0; i < 2; ++i) sigaction(kSignals[i], &action, &gPrevious[i]);
}

StopOnSignal::~StopOnSignal() {
  for (int i = 0; i < 2; ++i) sigaction(kSignals[i], &gPrevious[i], nullptr);
}

bool StopOnSignal::requested() const { return gSignal != 0; }

std::string StopOnSignal::signalName() const {
  if (gSignal == SIGINT) return "SIGINT";
  if (gSignal == SIGTERM) return "SIGTERM";
  return "";
}

int StopOnSignal::exitCode() const { return gSignal != 0 ? 128 + int(gSignal) : 0; }

}  // namespace mixtrace
