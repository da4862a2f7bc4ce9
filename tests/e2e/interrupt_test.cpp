// Ctrl-C during a render (issue 11, point 7): SIGINT (and SIGTERM) stop the render after the
// sample pass in flight; what has been rendered is written (the EXR header and the stats say how
// many spp) and the exit status is 128 + the signal; a second signal ends the process at once.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/stop_on_signal.h"
#include "output/exr_io.h"
#include "support/run_binary.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

constexpr int kTargetSpp = 1000000;   // far more than a few seconds render

// Starts `mixtrace args...` with stderr to `errPath`; returns its pid.
pid_t start(const std::vector<std::string>& args, const fs::path& errPath) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDERR_FILENO);
    std::vector<char*> argv{const_cast<char*>(MIXTRACE_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(MIXTRACE_BINARY, argv.data());
    ::_exit(127);
  }
  return pid;
}

// Waits up to `seconds` for the child; returns its wait status, or -1 (after killing it).
int waitFor(pid_t pid, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

// Waits until the render has started its sample passes: the "scene ...:" line comes right
// before them, once the signal handlers are in place.
bool waitForRendering(const fs::path& errPath, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (readText(errPath).find("mixtrace: scene ") != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

void stopMidRender(const std::string& backend, int signal, const std::string& signalName) {
  const fs::path dir = scratchDir("interrupt-" + backend + signalName);
  const fs::path exr = dir / "partial.exr", stats = dir / "partial.json", err = dir / "stderr.txt";
  const pid_t pid = start({"render", "--backend", backend, "--width", "32", "--height", "24", "--spp",
                           std::to_string(kTargetSpp), "--out", exr.string(), "--stats", stats.string()},
                          err);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitForRendering(err, 120.0)) << readText(err);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));   // a few sample passes
  ::kill(pid, signal);
  const int status = waitFor(pid, 60.0);
  ASSERT_NE(status, -1) << "did not stop within a minute: " << readText(err);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by a signal instead of writing: " << readText(err);
  EXPECT_EQ(WEXITSTATUS(status), 128 + signal) << readText(err);
  ASSERT_TRUE(fs::exists(exr)) << readText(err);
  ExrMetadata meta;
  const Image image = readExr(exr.string(), &meta);
  EXPECT_EQ(image.width, 32);
  EXPECT_GT(meta.ints["spp"], 0);
  EXPECT_LT(meta.ints["spp"], kTargetSpp);
  EXPECT_EQ(meta.ints["targetSpp"], kTargetSpp);
  EXPECT_EQ(meta.strings["interrupted"], signalName);
  const nlohmann::json j = nlohmann::json::parse(readText(stats));
  EXPECT_EQ(j["spp"].get<int>(), meta.ints["spp"]);
  EXPECT_TRUE(j["interrupted"].get<bool>());
  EXPECT_EQ(j["interrupted_by"], signalName);
  EXPECT_TRUE(fs::exists(dir / "partial.png"));
}

}  // namespace

TEST(Interrupt, SigintWritesWhatHasBeenRenderedCpu) { stopMidRender("cpu", SIGINT, "SIGINT"); }
TEST(Interrupt, SigintWritesWhatHasBeenRenderedVulkan) { stopMidRender("vulkan", SIGINT, "SIGINT"); }
TEST(Interrupt, SigtermLikewise) { stopMidRender("cpu", SIGTERM, "SIGTERM"); }

// The second signal is not caught: the process ends at once, by that signal.
TEST(Interrupt, ASecondSignalAbortsAtOnce) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    StopOnSignal stop(false);
    std::raise(SIGINT);
    if (!stop.requested() || stop.exitCode() != 130 || stop.signalName() != "SIGINT") ::_exit(3);
    std::raise(SIGINT);
    ::_exit(4);   // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_FALSE(WIFEXITED(status)) << "exit status " << WEXITSTATUS(status) << " (3: first signal not caught)";
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGINT);
}

// Outside a render (before it, after it) SIGINT keeps its default meaning.
TEST(Interrupt, HandlersAreRestoredAfterwards) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    { StopOnSignal stop(false); }
    std::raise(SIGINT);
    ::_exit(5);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
}
