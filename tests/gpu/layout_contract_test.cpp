// The host/GPU layout contract, seen from the shader compiler's side. host/vulkan/layout_checks.cpp
// pins the C++ layout of every shared struct to numbers derived from the scalar layout rules; this
// test reads the SPIR-V embedded in the binary (what glslang actually laid out) and compares every
// member offset of every struct the shaders place in a buffer or push-constant block with offsetof
// of the C++ struct of the same name, so a member that exists, or is padded, on one side only
// fails here. Nothing is compiled at run time and no device is needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cms/pixel_estimate_interface.h"
#include "cms/solve_interface.h"
#include "cms/sparse_solve_interface.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/display.h"
#include "shared/layouts.h"
#include "support/spirv_reader.h"
#include "tests/cell_lookup_interface.h"
#include "tests/float_mode_interface.h"
#include "tests/pair_lookup_interface.h"
#include "tests/texel_rows_interface.h"
#include "tests/trace_rays_interface.h"
#include "viewer/display_interface.h"
#include "vulkan/buffer_rows.h"
#include "vulkan/compute_pass.h"
#include "vulkan/embedded_shaders.h"
#include "wavefront/accumulate_interface.h"
#include "wavefront/aov_interface.h"
#include "wavefront/fused_interface.h"
#include "wavefront/generate_interface.h"
#include "wavefront/intersect_interface.h"
#include "wavefront/prepare_interface.h"
#include "wavefront/shade_interface.h"
#include "wavefront/shadow_interface.h"

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
  // The structs of rows read as texels (TEXELS) need lie in no GLSL buffer: shaders/gpu/buffers.glsl
  // assembles them from RGBA32UI texels, which tests/gpu/texel_rows_test.cpp checks bit for bit
  // (its kernel writes each to a buffer, so their offsets are checked here too).
  std::set<std::string> texelTypes;
#define TEXEL_ROW_TYPE(ID, name, binding, access, Type, extent, label) \
  if (BUFFER_IS_TEXELS_##access) texelTypes.insert(#Type);
  EVERY_BUFFER_ROW(TEXEL_ROW_TYPE)
#undef TEXEL_ROW_TYPE
  // ("float", "uint": word views, shared/cms_state.h CMS_STATE_VIEWS and CMS_PAIR_VIEWS, the
  // environment and the texels; "uvec4": the texture table, one texel per record.)
  EXPECT_EQ(texelTypes, (std::set<std::string>{"BvhNode", "TriangleGeom", "TriangleShading", "MaterialGpu", "LightGpu",
                                               "EmitterGpu", "LightBvhNodeGpu", "LightSelectionGpu", "ClusterGpu",
                                               "float", "uint", "uvec4"}));
  // Structs a row stores as plain words (the texture table: uvec4s, read by textureFromWords, whose
  // word order tests/unit/shared/texture_wrap_test.cpp checks against these offsets).
  const std::set<std::string> wordTypes = {"TextureGpu"};
  for (const auto& [name, layout] : cpp) {
    if (!texelTypes.count(name) && !wordTypes.count(name))
      EXPECT_TRUE(seen.count(name)) << name << " was found in no embedded shader";
  }
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

// What each module's interface header declares (shaders/*/*_interface.h): the buffers its
// descriptor set holds, in the order the host builds it, and its push-constant struct.
struct Interface {
  std::vector<uint32_t> bindings;
  std::string constants;
  size_t constantBytes;
  std::vector<uint32_t> unread = {};  // its *_UNREAD_BUFFERS: declared, never read (gpu/buffers.glsl)
};
std::map<std::string, Interface> interfaces() {
#define INTERFACE(LIST, S) Interface{BINDINGS_OF(LIST), #S, sizeof(shared::S)}
#define INTERFACE_WITH_UNREAD(LIST, S, UNREAD) Interface{BINDINGS_OF(LIST), #S, sizeof(shared::S), BINDINGS_OF(UNREAD)}
  return {
      {"generate", INTERFACE(GENERATE_BUFFERS, GenerateConstants)},
      {"prepare", INTERFACE(PREPARE_BUFFERS, PrepareConstants)},
      {"intersect", INTERFACE(INTERSECT_BUFFERS, IntersectConstants)},
      {"shade", INTERFACE(SHADE_BUFFERS, VertexConstants)},
      {"shade_float_atomics", INTERFACE(SHADE_BUFFERS, VertexConstants)},
      {"shadow", INTERFACE_WITH_UNREAD(SHADOW_BUFFERS, VertexConstants, SHADOW_UNREAD_BUFFERS)},
      {"shadow_float_atomics", INTERFACE_WITH_UNREAD(SHADOW_BUFFERS, VertexConstants, SHADOW_UNREAD_BUFFERS)},
      {"accumulate", INTERFACE(ACCUMULATE_BUFFERS, AccumulateConstants)},
      {"fused", INTERFACE(FUSED_BUFFERS, FusedConstants)},
      {"aov", INTERFACE_WITH_UNREAD(AOV_BUFFERS, AovConstants, AOV_UNREAD_BUFFERS)},
      {"pixel_estimate", INTERFACE(PIXEL_ESTIMATE_BUFFERS, PixelEstimateConstants)},
      {"solve", INTERFACE(SOLVE_BUFFERS, SolveParams)},
      {"sparse_solve", INTERFACE(SPARSE_SOLVE_BUFFERS, SparseSolveConstants)},
      {"display", INTERFACE_WITH_UNREAD(DISPLAY_BUFFERS, DisplayConstants, DISPLAY_UNREAD_BUFFERS)},
      {"trace_rays", INTERFACE(TRACE_RAYS_BUFFERS, TraceRaysConstants)},
      {"cell_lookup", INTERFACE(CELL_LOOKUP_BUFFERS, CellLookupConstants)},
      {"pair_lookup", INTERFACE(PAIR_LOOKUP_BUFFERS, PairLookupConstants)},
      {"texel_rows", INTERFACE(TEXEL_ROWS_BUFFERS, TexelRowsConstants)},
      {"float_mode", INTERFACE(FLOAT_MODE_BUFFERS, FloatModeConstants)},
  };
#undef INTERFACE
#undef INTERFACE_WITH_UNREAD
}

// Every module pushes its interface's struct, which is the whole range of its pipeline layout
// (host/vulkan/compute_pass.h) and fits the 128 bytes every device holds.
TEST(LayoutContract, PushConstantBlocksAreTheInterfacesStruct) {
  const std::map<std::string, Interface> declared = interfaces();
  size_t modulesWithPushConstants = 0;
  for (const std::string& module : embeddedShaderNames()) {
    const auto interface = declared.find(module);
    ASSERT_NE(interface, declared.end()) << module << ": a module without an interface in this test";
    const testing::SpirvLayout spirv = readModule(module);
    const std::vector<uint32_t> blocks = spirv.pushConstantBlocks();
    ASSERT_LE(blocks.size(), 1u) << module;
    if (blocks.empty()) continue;
    ++modulesWithPushConstants;
    const uint32_t bytes = spirv.byteSize(blocks[0]);
    EXPECT_EQ(bytes, interface->second.constantBytes) << module << ": push constants other than the host's range";
    EXPECT_LE(bytes, 128u) << module << ": push constants beyond maxPushConstantsSize's guaranteed minimum";
    for (const testing::SpirvLayout::Struct& s : spirv.structs())
      if (s.id == blocks[0]) {
        ASSERT_EQ(s.members.size(), 1u) << module;
        for (const testing::SpirvLayout::Struct& inner : spirv.structs())
          if (inner.id == s.members[0].type) EXPECT_EQ(inner.name, interface->second.constants) << module;
      }
  }
  EXPECT_EQ(modulesWithPushConstants, declared.size());  // every pass has constants
}

// The buffers a compiled module reads or writes are exactly those its interface lists: the host
// binds that list (a buffer missing from it would be an invalid pipeline; one the pass does not
// read would be bound for nothing). The optimized modules declare only what their code uses; the
// float-atomic variants are left unoptimized by glslang (its optimizer does not take their
// capability) and also keep the declarations of the interface's unread rows, which no
// instruction reaches. Each pass binds at most the 32 storage buffers lavapipe offers one stage.
TEST(LayoutContract, EveryPassBindsWhatItReads) {
  const std::map<std::string, Interface> declared = interfaces();
  for (const std::string& module : embeddedShaderNames()) {
    const auto interface = declared.find(module);
    ASSERT_NE(interface, declared.end()) << module;
    std::vector<uint32_t> listed = interface->second.bindings;
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end()) << module << ": a row listed twice";
    EXPECT_LE(listed.size(), 32u) << module;
    const std::vector<uint32_t> inModule = readModule(module).bindings();
    const bool unoptimized = module.find("_float_atomics") != std::string::npos;
    if (!unoptimized) {
      EXPECT_EQ(inModule, listed) << module << ": bindings (SPIR-V, interface)";
      continue;
    }
    std::vector<uint32_t> listedOrUnread = listed;
    listedOrUnread.insert(listedOrUnread.end(), interface->second.unread.begin(), interface->second.unread.end());
    std::sort(listedOrUnread.begin(), listedOrUnread.end());
    EXPECT_TRUE(std::includes(inModule.begin(), inModule.end(), listed.begin(), listed.end())) << module;
    EXPECT_TRUE(std::includes(listedOrUnread.begin(), listedOrUnread.end(), inModule.begin(), inModule.end()))
        << module << ": declares a buffer its interface does not list";
  }
}

}  // namespace
}  // namespace mixtrace
