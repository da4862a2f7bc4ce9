// "Code paths a scene does not need are not compiled into its pipelines": for each scene feature a
// specialization constant switches (shared/bindings.h), the embedded module of a pass that holds
// its code is specialised with the feature off and on, as a driver would (spirv-opt: the constant
// frozen, the spec-constant expressions over it folded, then the usual optimisation, which removes
// the branches they decide), and the module with
// the feature off must be smaller by the feature's code. A feature test that stopped reading its
// constant (an `if (true)` in its place, a helper called unconditionally) fails here.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shared/bindings.h"
#include "shared/layouts.h"
#include "support/run_binary.h"
#include "vulkan/embedded_shaders.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;

// Instructions in a SPIR-V file (the header is 5 words; each instruction's first word holds its
// word count in the high half).
size_t instructionCount(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<uint32_t> words;
  uint32_t w;
  while (in.read(reinterpret_cast<char*>(&w), sizeof(w))) words.push_back(w);
  size_t count = 0;
  for (size_t i = 5; i < words.size(); i += std::max<uint32_t>(1u, words[i] >> 16)) ++count;
  return count;
}

// The module `name` with spec constant `id` frozen at `value` ("true", "false" or a number),
// optimised; its instruction count.
size_t specialisedSize(const std::string& name, int id, const std::string& value, const fs::path& dir) {
  const EmbeddedShader* shader = findEmbeddedShader(name.c_str());
  if (!shader) throw std::runtime_error("no embedded shader " + name);
  const fs::path in = dir / (name + ".spv"), out = dir / (name + "-" + std::to_string(id) + "-" + value + ".spv");
  std::ofstream(in, std::ios::binary).write(reinterpret_cast<const char*>(shader->code), std::streamsize(shader->sizeBytes));
  const std::string command = std::string(SPIRV_OPT) + " --set-spec-const-default-value \"" + std::to_string(id) + ":" + value +
                              "\" --freeze-spec-const --fold-spec-const-op-composite -O " + in.string() + " -o " +
                              out.string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return instructionCount(out);
}

struct FeatureCase {
  const char* feature;
  int specId;
  const char* module;
  size_t minimumSaved;   // instructions the feature's code takes at least (measured, with margin)
};

class SpecializationSpirv : public ::testing::TestWithParam<FeatureCase> {};

TEST_P(SpecializationSpirv, AFeatureSwitchedOffLeavesNoneOfItsCode) {
  const FeatureCase c = GetParam();
  const fs::path dir = mixtrace::testing::scratchDir("spirv");
  const size_t on = specialisedSize(c.module, c.specId, "true", dir);
  const size_t off = specialisedSize(c.module, c.specId, "false", dir);
  std::printf("%s in %s: %zu instructions on, %zu off\n", c.feature, c.module, on, off);
  EXPECT_GE(on, off + c.minimumSaved) << c.feature << " in " << c.module;
}

INSTANTIATE_TEST_SUITE_P(Features, SpecializationSpirv,
                         // Measured (instructions on / off, the light selection at its default, power):
                         // alpha 1408 / 548 in intersect, 1402 / 537 in shadow; vertex colours 9657 /
                         // 9614, environment 9657 / 8848, textures 9657 / 5275, normal maps 9657 / 8855,
                         // transmission 9657 / 7189, second texture coordinates 9657 / 9533 in shade
                         // (1408 / 1357 in intersect).
                         ::testing::Values(FeatureCase{"alpha", SPEC_HAS_ALPHA, "intersect", 400},
                                           FeatureCase{"alpha", SPEC_HAS_ALPHA, "shadow", 400},
                                           FeatureCase{"vertex_colours", SPEC_HAS_VERTEX_COLORS, "shade", 30},
                                           FeatureCase{"environment", SPEC_HAS_ENVIRONMENT, "shade", 600},
                                           FeatureCase{"textures", SPEC_HAS_TEXTURES, "shade", 1000},
                                           FeatureCase{"normal_maps", SPEC_HAS_NORMAL_MAPS, "shade", 50},
                                           FeatureCase{"transmission", SPEC_HAS_TRANSMISSION, "shade", 1500},
                                           FeatureCase{"second_uvs", SPEC_HAS_SECOND_UVS, "shade", 60},
                                           FeatureCase{"second_uvs", SPEC_HAS_SECOND_UVS, "intersect", 25}),
                         [](const auto& info) {
                           return std::string(info.param.feature) + "_" + info.param.module;
                         });

// The method's light selection is a constant too (SPEC_LIGHT_SELECTION): a method that picks lights
// by power has none of the light BVH's code in its vertex passes, and one that picks by the light
// BVH none of the uniform selection's (lavapipe runs both sides of a branch, so a push constant
// here cost the shade pass a quarter of its time). Measured (instructions, bvh / power / uniform):
// shade 12803 / 9657 / 9648, fused 13251 / 11378 / 11363.
TEST(SpecializationSpirv, TheLightSelectionLeavesNoneOfTheOthersCode) {
  const fs::path dir = mixtrace::testing::scratchDir("spirv");
  const std::string uniform = std::to_string(shared::kLightSelectUniform);
  const std::string power = std::to_string(shared::kLightSelectPower);
  const std::string bvh = std::to_string(shared::kLightSelectBvh);
  for (const char* module : {"shade", "fused"}) {
    const size_t withBvh = specialisedSize(module, SPEC_LIGHT_SELECTION, bvh, dir);
    const size_t withPower = specialisedSize(module, SPEC_LIGHT_SELECTION, power, dir);
    const size_t withUniform = specialisedSize(module, SPEC_LIGHT_SELECTION, uniform, dir);
    std::printf("light selection in %s: %zu instructions with bvh, %zu power, %zu uniform\n", module, withBvh,
                withPower, withUniform);
    EXPECT_GE(withBvh, withPower + 1500) << module;
    EXPECT_GT(withPower, withUniform) << module;
  }
}

}  // namespace
