#pragma once
// Renders a test scene with the real mixtrace binary and reads back the mean and the variance of
// the mean.
#include <filesystem>
#include <string>

#include "output/exr_io.h"
#include "output/image.h"
#include "support/run_binary.h"

namespace mixtrace::testing::analytic {

struct RenderSettings {
  int width = 32;
  int height = 32;
  int spp = 256;
  int maxDepth = 2;
  std::string method = "pt-power";
  std::string backend = "vulkan";
  unsigned seed = 1;
};

struct RenderedImage {
  std::string error;  // non-empty: the render failed (exit code and stderr)
  Image mean;
  Image variance;
};

inline RenderedImage renderWithVariance(const std::filesystem::path& scene, const RenderSettings& s,
                                        const std::filesystem::path& out) {
  RenderedImage result;
  const RunResult run = runMixtrace("render " + scene.string() + " --width " + std::to_string(s.width) + " --height " +
                                    std::to_string(s.height) + " --spp " + std::to_string(s.spp) + " --max-depth " +
                                    std::to_string(s.maxDepth) + " --method " + s.method + " --backend " + s.backend +
                                    " --seed " + std::to_string(s.seed) + " --variance -q --no-png --out " + out.string());
  if (run.exitCode != 0) {
    result.error = "exit code " + std::to_string(run.exitCode) + ": " + run.stderrText;
    return result;
  }
  result.mean = readExr(out.string(), nullptr, &result.variance);
  if (result.variance.width != result.mean.width || result.variance.height != result.mean.height) {
    result.error = "the EXR has no variance channels";
  }
  return result;
}

}  // namespace mixtrace::testing::analytic
