// The host/GPU layout contract, seen from the shader compiler's side. host/vulkan/layout_checks.cpp
// pins the C++ layout of every shared struct to numbers derived from the scalar layout rules; this
// test reads the SPIR-V embedded in the binary (what glslang actually laid out) and compares every
// member offset of every struct the shaders place in a buffer or push-constant block with offsetof
// of the C++ struct of the same name, so a member that exists, or is padded, on one side only
// fails here. Nothing is compiled at run time and no device is needed.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/display.h"
#include "shared/layouts.h"
#include "support/spirv_reader.h"
#include "vulkan/embedded_shaders.h"

namespace mixtrace {
namespace {

struct CppMember {
  std::string name;
  size_t offset;
};
struct CppStruct {
  size_t size = 0;
  std::vector<CppMember> members;  // in declaration order
};

// The C++ side, as the compiler lays it out, for every struct of the contract table.
std::map<std::string, CppStruct> cppLayouts() {
  std::map<std::string, CppStruct> table;
#define LAYOUT_STRUCT(S, expectedSize) table[#S].size = sizeof(shared::S);
#define LAYOUT_MEMBER(S, member, expectedOffset) table[#S].members.push_back({#member, offsetof(shared::S, member)});
#include "vulkan/gpu_layout_table.inc"
#undef LAYOUT_STRUCT
#undef LAYOUT_MEMBER
  return table;
}

// Every embedded module: one per shaders/{wavefront,cms,viewer,tests}/*.comp (as CMakeLists.txt
// globs them) plus the float-atomics variants of shade and shadow.
std::vector<std::string> embeddedShaderNames() {
  std::vector<std::string> names = {"shade_float_atomics", "shadow_float_atomics"};
  for (const char* folder : {"wavefront", "cms", "viewer", "tests"})
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(MIXTRACE_SOURCE_DIR) / "shaders" / folder))
      if (entry.path().extension() == ".comp") names.push_back(entry.path().stem().string());
  return names;
}

testing::SpirvLayout readModule(const std::string& name) {
  const EmbeddedShader* shader = findEmbeddedShader(name.c_str());
  if (!shader) throw std::runtime_error("no embedded shader " + name);
  return testing::SpirvLayout(shader->code, shader->sizeBytes / sizeof(uint32_t));
}

TEST(LayoutContract, EveryEmbeddedShaderIsFound) {
  const std::vector<std::string> names = embeddedShaderNames();
  EXPECT_GE(names.size(), 12u);
  for (const std::string& name : names) EXPECT_NE(findEmbeddedShader(name.c_str()), nullptr) << name;
}

// Each struct with an explicit layout in a module is compared member by member; every struct of
// the table must be met in at least one module, so no row of the contract goes unchecked.
TEST(LayoutContract, GlslOffsetsAndStridesEqualCpp) {
  const std::map<std::string, CppStruct> cpp = cppLayouts();
  std::set<std::string> seen;
  for (const std::string& module : embeddedShaderNames()) {
    const testing::SpirvLayout spirv = readModule(module);
    for (const testing::SpirvLayout::Struct& s : spirv.structs()) {
      if (s.isBlock || !s.hasExplicitLayout()) continue;  // the block wrappers; function-local copies
      const auto found = cpp.find(s.name);
      if (found == cpp.end()) {
        ADD_FAILURE() << module << ": struct " << s.name << " lies in a buffer but is not in "
                      << "host/vulkan/gpu_layout_table.inc (add it, with its expected offsets)";
        continue;
      }
      const CppStruct& c = found->second;
      seen.insert(s.name);
      const std::string where = module + ": " + s.name;
      // Matched by name, so one extra member reports itself and every offset it moves.
      std::map<std::string, size_t> cppOffsets;
      for (const CppMember& m : c.members) cppOffsets[m.name] = m.offset;
      std::set<std::string> glslNames;
      for (const testing::SpirvLayout::Member& m : s.members) {
        glslNames.insert(m.name);
        const auto offset = cppOffsets.find(m.name);
        if (offset == cppOffsets.end()) ADD_FAILURE() << where << "::" << m.name << " exists in GLSL only";
        else EXPECT_EQ(size_t(*m.offset), offset->second) << where << "::" << m.name << ": offset (GLSL, C++)";
      }
      for (const CppMember& m : c.members)
        if (!glslNames.count(m.name)) ADD_FAILURE() << where << "::" << m.name << " exists in C++ only";
      // The scalar layout adds no tail padding: the struct ends where its last member does, which
      // is also its array stride, and C++'s sizeof must be that.
      EXPECT_EQ(size_t(spirv.byteSize(s.id)), c.size) << where << ": size";
      for (uint32_t stride : spirv.arrayStridesOf(s.id)) EXPECT_EQ(size_t(stride), c.size) << where << ": array stride";
    }
  }
  for (const auto& [name, layout] : cpp) EXPECT_TRUE(seen.count(name)) << name << " was found in no embedded shader";
}

// Buffers of bare scalars and vectors (ray origins, throughput, film: vec3; cell keys: uint64_t)
// hold C++ arrays of float, uint, glm::vec3, uint64_t: tightly packed, as only the scalar layout
// packs them (std430 would give a vec3 array a 16-byte stride). Struct arrays are checked above.
TEST(LayoutContract, BareArraysArePacked) {
  size_t arrays = 0;
  for (const std::string& module : embeddedShaderNames()) {
    const testing::SpirvLayout spirv = readModule(module);
    std::set<uint32_t> structIds;
    for (const testing::SpirvLayout::Struct& s : spirv.structs()) structIds.insert(s.id);
    for (const auto& [element, stride] : spirv.arrayStrides()) {
      if (structIds.count(element)) continue;
      ++arrays;
      EXPECT_EQ(stride, spirv.byteSize(element)) << module << ": an array of type %" << element << " is not packed";
    }
  }
  EXPECT_GT(arrays, 0u);
}

// Every pass pushes its struct into the one range of the shared pipeline layout,
// sizeof(PassConstants) bytes (host/render/wavefront_renderer.cpp), which every device holds.
TEST(LayoutContract, PushConstantBlocksFitTheRange) {
  const std::set<std::string> pushed = {"PassConstants", "SolveParams", "DisplayConstants"};
  size_t modulesWithPushConstants = 0;
  for (const std::string& module : embeddedShaderNames()) {
    const testing::SpirvLayout spirv = readModule(module);
    const std::vector<uint32_t> blocks = spirv.pushConstantBlocks();
    ASSERT_LE(blocks.size(), 1u) << module;
    if (blocks.empty()) continue;
    ++modulesWithPushConstants;
    const uint32_t bytes = spirv.byteSize(blocks[0]);
    EXPECT_LE(bytes, sizeof(shared::PassConstants)) << module << ": push constants beyond the pipeline layout's range";
    EXPECT_LE(bytes, 128u) << module << ": push constants beyond maxPushConstantsSize's guaranteed minimum";
    for (const testing::SpirvLayout::Struct& s : spirv.structs())
      if (s.id == blocks[0]) {
        ASSERT_EQ(s.members.size(), 1u) << module;
        for (const testing::SpirvLayout::Struct& inner : spirv.structs())
          if (inner.id == s.members[0].type)
            EXPECT_TRUE(pushed.count(inner.name)) << module << ": pushes " << inner.name;
      }
  }
  EXPECT_GE(modulesWithPushConstants, 3u);  // at least the wavefront passes, the solve, the display
}

}  // namespace
}  // namespace mixtrace
