#pragma once
// Runs the mixtrace binary (or any shell command) from a test and captures its exit code and
// stderr. Every run is wrapped in `timeout` so that a hang fails the test instead of the suite.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace mixtrace::testing {

struct RunResult {
  int exitCode = -1;
  std::string stdoutText;
  std::string stderrText;
  std::vector<std::string> stderrLines() const {
    std::vector<std::string> lines;
    std::istringstream in(stderrText);
    for (std::string l; std::getline(in, l);)
      if (!l.empty()) lines.push_back(l);
    return lines;
  }
};

inline std::filesystem::path scratchDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("mixtrace-test-" + name + "-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// `args` is appended to the binary path verbatim (shell syntax); `env` is prefixed (e.g. "VAR=x").
inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline RunResult runMixtrace(const std::string& args, const std::string& env = "", int timeoutSeconds = 120) {
  auto dir = scratchDir("run");
  auto outFile = dir / "stdout.txt", errFile = dir / "stderr.txt";
  std::string cmd = env + " timeout " + std::to_string(timeoutSeconds) + " " + MIXTRACE_BINARY + " " + args + " > " +
                    outFile.string() + " 2> " + errFile.string();
  int status = std::system(cmd.c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.stdoutText = readText(outFile);
  r.stderrText = readText(errFile);
  return r;
}

inline void writeFile(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

}  // namespace mixtrace::testing
