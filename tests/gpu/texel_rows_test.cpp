// The rows the passes read as texels (access TEXELS: BVH nodes, triangles, triangle shading data,
// materials, lights, emitters, light BVH nodes, the light selection, the clusters, and the word
// views of the cell solutions, pair coefficients and cluster defaults, the texture table, the
// texels and the environment's words) come back from their GLSL accessors bit for bit as the host wrote
// them: random words in every member, including the bit patterns of NaNs, infinities and -1,
// which a float view could alter (shaders/tests/texel_rows.comp).
#include <cstring>
#include <iterator>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "shared/layouts.h"
#include "tests/texel_rows_interface.h"
#include "vulkan/buffer.h"
#include "vulkan/buffer_rows.h"
#include "vulkan/compute_pass.h"
#include "vulkan/context.h"

namespace mixtrace {
namespace {

// n elements of T filled with random words, every 8th word one of the special patterns.
template <class T> std::vector<T> randomElements(size_t n, std::mt19937& rng) {
  static_assert(sizeof(T) % 4 == 0, "whole words");
  const uint32_t special[] = {0xffffffffu, 0x7fc00001u, 0xff800000u, 0x7f800000u, 0x80000000u, 0x00000001u};
  std::vector<uint32_t> words(n * sizeof(T) / 4);
  for (size_t i = 0; i < words.size(); ++i) words[i] = i % 8 == 3 ? special[(i / 8) % std::size(special)] : rng();
  std::vector<T> out(n);
  std::memcpy(out.data(), words.data(), words.size() * 4);
  return out;
}

template <class T> void expectSameBits(const Buffer& buffer, const std::vector<T>& expected, const char* row) {
  std::vector<T> got = buffer.downloadAll<T>();
  ASSERT_GE(got.size(), expected.size()) << row;
  for (size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(std::memcmp(&got[i], &expected[i], sizeof(T)), 0) << row << " element " << i;
}

TEST(TexelRows, EveryAccessorReadsBackTheHostsBits) {
  VulkanContext ctx(ContextOptions{"", true});
  std::mt19937 rng(7);
  constexpr size_t n = 300;
  auto nodes = randomElements<shared::BvhNode>(n, rng);
  auto shading = randomElements<shared::TriangleShading>(n, rng);
  auto materials = randomElements<shared::MaterialGpu>(n, rng);
  auto emitters = randomElements<shared::EmitterGpu>(n, rng);
  auto lightNodes = randomElements<shared::LightBvhNodeGpu>(n, rng);
  auto triangles = randomElements<shared::TriangleGeom>(n, rng);
  auto lights = randomElements<shared::LightGpu>(n, rng);
  auto selection = randomElements<shared::LightSelectionGpu>(n, rng);
  auto clusters = randomElements<shared::ClusterGpu>(n, rng);
  auto solutionWords = randomElements<uint32_t>(n, rng);   // n is a multiple of 4: whole texels
  auto alphaWords = randomElements<uint32_t>(n, rng);
  auto defaultWords = randomElements<uint32_t>(n, rng);
  auto textureTable = randomElements<glm::uvec4>(n, rng);
  auto texelWords = randomElements<uint32_t>(n, rng);
  auto environmentWords = randomElements<uint32_t>(n, rng);
  static_assert(n % 4 == 0, "the word views are read as whole texels");
  Buffer in[] = {makeBuffer(ctx, nodes, "nodes"), makeBuffer(ctx, shading, "shading"),
                 makeBuffer(ctx, materials, "materials"), makeBuffer(ctx, emitters, "emitters"),
                 makeBuffer(ctx, lightNodes, "light nodes"), makeBuffer(ctx, triangles, "triangles"),
                 makeBuffer(ctx, lights, "lights"), makeBuffer(ctx, selection, "light selection"),
                 makeBuffer(ctx, clusters, "clusters"), makeBuffer(ctx, solutionWords, "cell solutions"),
                 makeBuffer(ctx, alphaWords, "pair alphas"), makeBuffer(ctx, defaultWords, "cluster defaults"),
                 makeBuffer(ctx, textureTable, "texture table"), makeBuffer(ctx, texelWords, "texels"),
                 makeBuffer(ctx, environmentWords, "environment")};
  Buffer out[] = {Buffer(ctx, n * sizeof(shared::BvhNode), "out"), Buffer(ctx, n * sizeof(shared::TriangleShading), "out"),
                  Buffer(ctx, n * sizeof(shared::MaterialGpu), "out"), Buffer(ctx, n * sizeof(shared::EmitterGpu), "out"),
                  Buffer(ctx, n * sizeof(shared::LightBvhNodeGpu), "out"), Buffer(ctx, n * sizeof(shared::TriangleGeom), "out"),
                  Buffer(ctx, n * sizeof(shared::LightGpu), "out"), Buffer(ctx, n * sizeof(shared::LightSelectionGpu), "out"),
                  Buffer(ctx, n * sizeof(shared::ClusterGpu), "out"), Buffer(ctx, n * 4, "out"), Buffer(ctx, n * 4, "out"),
                  Buffer(ctx, n * 4, "out"), Buffer(ctx, n * 16, "out"), Buffer(ctx, n * 4, "out"),
                  Buffer(ctx, n * 4, "out")};
  const uint32_t inBindings[] = {shared::BINDING_BVH_NODES, shared::BINDING_TRIANGLE_SHADING, shared::BINDING_MATERIALS,
                                 shared::BINDING_EMITTERS, shared::BINDING_LIGHT_BVH, shared::BINDING_TRIANGLES,
                                 shared::BINDING_LIGHTS, shared::BINDING_LIGHT_SELECTION, shared::BINDING_CLUSTERS,
                                 shared::BINDING_CELL_SOLUTION_TEXELS, shared::BINDING_PAIR_ALPHA_TEXELS,
                                 shared::BINDING_CLUSTER_DEFAULTS_TEXELS, shared::BINDING_TEXTURES,
                                 shared::BINDING_TEXELS, shared::BINDING_ENVIRONMENT};
  const uint32_t outBindings[] = {shared::BINDING_BVH_NODES_OUT, shared::BINDING_TRIANGLE_SHADING_OUT,
                                  shared::BINDING_MATERIALS_OUT, shared::BINDING_EMITTERS_OUT,
                                  shared::BINDING_LIGHT_BVH_OUT, shared::BINDING_TRIANGLES_OUT, shared::BINDING_LIGHTS_OUT,
                                  shared::BINDING_LIGHT_SELECTION_OUT, shared::BINDING_CLUSTERS_OUT,
                                  shared::BINDING_CELL_SOLUTION_OUT, shared::BINDING_PAIR_ALPHA_OUT,
                                  shared::BINDING_CLUSTER_DEFAULTS_OUT, shared::BINDING_TEXTURES_OUT,
                                  shared::BINDING_TEXELS_OUT, shared::BINDING_ENVIRONMENT_OUT};
  ComputePass pass(ctx, "texel_rows", BINDINGS_OF(TEXEL_ROWS_BUFFERS), sizeof(shared::TexelRowsConstants), {});
  static_assert(std::size(in) == std::size(inBindings) && std::size(out) == std::size(outBindings), "one binding per row");
  for (size_t r = 0; r < std::size(in); ++r) {
    EXPECT_TRUE(isTexelBinding(inBindings[r])) << "row " << r << " is read as texels";
    pass.bind(inBindings[r], in[r]);
    pass.bind(outBindings[r], out[r]);
  }
  shared::TexelRowsConstants pc{uint32_t(n)};
  ctx.submitAndWait([&](VkCommandBuffer cmd) { pass.dispatch(cmd, &pc, sizeof(pc), workgroupsFor(uint32_t(n))); });
  expectSameBits(out[0], nodes, "BVH nodes");
  expectSameBits(out[1], shading, "triangle shading");
  expectSameBits(out[2], materials, "materials");
  expectSameBits(out[3], emitters, "emitters");
  expectSameBits(out[4], lightNodes, "light BVH nodes");
  expectSameBits(out[5], triangles, "triangles");
  expectSameBits(out[6], lights, "lights");
  expectSameBits(out[7], selection, "light selection");
  expectSameBits(out[8], clusters, "clusters");
  expectSameBits(out[9], solutionWords, "cell solution words");
  expectSameBits(out[10], alphaWords, "pair alpha words");
  expectSameBits(out[11], defaultWords, "cluster default words");
  expectSameBits(out[12], textureTable, "texture table");
  expectSameBits(out[13], texelWords, "texels");
  expectSameBits(out[14], environmentWords, "environment words");
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace mixtrace
