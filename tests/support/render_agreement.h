#pragma once
// Renders two generated glTF scenes with the real binary (--variance) and compares them with the
// project's per-pixel statistical test (compare/image_compare.h). For tests whose claim is "this
// scene renders like that one" (scale invariance, far-away geometry, extreme emission).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"

namespace mixtrace::testing {

// Small and few samples: these tests look for biases of 20 % and more (a black image, a darkened
// room), which 40x30 at 64 spp shows at many sigma, and they run on 2 cores.
inline const char* const kAgreementImage = "--width 40 --height 30 --spp 64";

// Where renderScene(dir, name, ..., backend, ...) writes its image.
inline std::filesystem::path agreementImagePath(const std::string& dir, const std::string& name,
                                                const std::string& backend) {
  return scratchDir(dir) / (name + "-" + backend + ".exr");
}

// Writes `gltf` as `name`.gltf in the scratch directory `dir` and renders it on `backend` with
// `seed`; fails the calling test (fatally) when the binary fails or writes no variance.
inline void renderScene(const std::string& dir, const std::string& name, const std::string& gltf,
                        const std::string& backend, int seed, RenderWithStats& out) {
  const std::filesystem::path d = scratchDir(dir);
  const std::filesystem::path scene = d / (name + ".gltf"), image = agreementImagePath(dir, name, backend);
  writeFile(scene, gltf);
  out = renderWithStats(scene.string() + " " + kAgreementImage + " --method pt-uniform --backend " + backend +
                            " --seed " + std::to_string(seed),
                        image, 600);
  ASSERT_EQ(out.exitCode, 0) << name << " on " << backend << ": " << out.stderrText;
  ASSERT_EQ(out.variance.width, out.mean.width) << name << ": no variance channels";
}

inline ComparisonResult compareRenders(const RenderWithStats& a, const RenderWithStats& b) {
  return compareImages(a.mean, a.variance, b.mean, b.variance);
}

}  // namespace mixtrace::testing
