#pragma once
// One `mixtrace render` with --variance and --stats, read back: the image, its standard errors
// and the stats JSON. For tests that check a render's statistics as well as its pixels.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "output/exr_io.h"
#include "support/run_binary.h"

namespace mixtrace::testing {

struct RenderWithStats {
  int exitCode = -1;
  std::string stderrText;
  // `variance` holds the standard errors of the pixel means (exr_io.h). Empty when the render
  // failed.
  Image mean, variance;
  nlohmann::json stats;
};

// `args`: everything after `render` but the outputs; the image goes to `out`, the stats next to it
// (.json).
inline RenderWithStats renderWithStats(const std::string& args, const std::filesystem::path& out, int timeoutSeconds) {
  const std::filesystem::path stats = std::filesystem::path(out).replace_extension(".json");
  const RunResult r = runMixtrace("render " + args + " --variance -q --no-png --out " + out.string() + " --stats " +
                                      stats.string(),
                                  "", timeoutSeconds);
  RenderWithStats result;
  result.exitCode = r.exitCode;
  result.stderrText = r.stderrText;
  if (r.exitCode != 0) return result;
  result.mean = readExr(out.string(), nullptr, &result.variance);
  result.stats = nlohmann::json::parse(readText(stats));
  return result;
}

}  // namespace mixtrace::testing
