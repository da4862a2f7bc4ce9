// Compile-time contracts of the host/GPU boundary: every struct the shaders read from a buffer or
// a push-constant block has, in C++, the size and member offsets the scalar block layout gives it
// in GLSL (host/vulkan/gpu_layout_table.inc derives them), and every push-constant block fits the
// range the pipeline layout declares and the range every Vulkan device guarantees. A layout
// change that breaks one of them fails the build here, not as a wrong image.
// tests/gpu/layout_contract_test.cpp checks the other half: that the compiled shaders (the
// embedded SPIR-V) see the same offsets.
#include <cstddef>
#include <cstdint>
#include <iterator>

#include <glm/glm.hpp>

#include "cms/pixel_estimate_interface.h"
#include "cms/solve_interface.h"
#include "shared/bindings.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_state.h"
#include "shared/cms_sparse_solve.h"
#include "shared/display.h"
#include "shared/layouts.h"
#include "tests/cell_lookup_interface.h"
#include "tests/float_mode_interface.h"
#include "tests/pair_lookup_interface.h"
#include "tests/texel_rows_interface.h"
#include "tests/trace_rays_interface.h"
#include "viewer/display_interface.h"
#include "vulkan/buffer_rows.h"
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

// The building blocks: C packs glm vectors as the scalar layout packs GLSL's (no SIMD alignment;
// GLM_FORCE_DEFAULT_ALIGNED_GENTYPES would break every vec3 member below). Buffers of bare vec3
// (ray origins, throughput, film) and of uint64_t (cell keys) rely on these too.
static_assert(sizeof(glm::vec2) == 8 && alignof(glm::vec2) == 4, "glm::vec2 must be GLSL's scalar vec2");
static_assert(sizeof(glm::vec3) == 12 && alignof(glm::vec3) == 4, "glm::vec3 must be GLSL's scalar vec3");
static_assert(sizeof(float) == 4 && sizeof(shared::uint) == 4 && sizeof(int) == 4, "32-bit scalars");
static_assert(sizeof(uint64_t) == 8, "the cell key table holds uint64_t");

// Every struct of the table: its size, 4-byte alignment (the scalar layout aligns each of these
// to its 4-byte components, so a C++ array of them has GLSL's array stride), and each offset.
#define LAYOUT_STRUCT(S, size)                                                                 \
  static_assert(sizeof(shared::S) == (size), #S ": size differs from its scalar GLSL layout"); \
  static_assert(alignof(shared::S) == 4, #S ": alignment must be 4, as in the scalar layout");
#define LAYOUT_MEMBER(S, member, offset)                 \
  static_assert(offsetof(shared::S, member) == (offset), \
                #S "::" #member ": offset differs from its scalar GLSL layout");
#include "vulkan/gpu_layout_table.inc"
#undef LAYOUT_STRUCT
#undef LAYOUT_MEMBER

// Push constants: every pass's pipeline layout has one range, exactly its own struct
// (host/vulkan/compute_pass.h), which must fit the 128 bytes every device guarantees
// (VkPhysicalDeviceLimits::maxPushConstantsSize) and be a multiple of 4 bytes.
constexpr size_t kGuaranteedPushConstantBytes = 128;
#define PUSH_CONSTANTS_FIT(S)                                                                    \
  static_assert(sizeof(shared::S) <= kGuaranteedPushConstantBytes,                              \
                #S ": push constants beyond the 128 bytes every device guarantees");            \
  static_assert(sizeof(shared::S) % 4 == 0, #S ": a push-constant range's size is a multiple of 4");
PUSH_CONSTANTS_FIT(GenerateConstants)
PUSH_CONSTANTS_FIT(PrepareConstants)
PUSH_CONSTANTS_FIT(IntersectConstants)
PUSH_CONSTANTS_FIT(VertexConstants)
PUSH_CONSTANTS_FIT(AccumulateConstants)
PUSH_CONSTANTS_FIT(AovConstants)
PUSH_CONSTANTS_FIT(PixelEstimateConstants)
PUSH_CONSTANTS_FIT(SolveParams)
PUSH_CONSTANTS_FIT(SparseSolveConstants)
PUSH_CONSTANTS_FIT(DisplayConstants)
PUSH_CONSTANTS_FIT(TraceRaysConstants)
PUSH_CONSTANTS_FIT(CellLookupConstants)
PUSH_CONSTANTS_FIT(PairLookupConstants)
PUSH_CONSTANTS_FIT(TexelRowsConstants)
#undef PUSH_CONSTANTS_FIT

// Binding numbers: one space for every buffer table (shaders/shared/buffer_table.h), so no two
// rows may share a number (a pass listing both would bind one buffer in place of the other).
#define ROW_BINDING(ID, name, binding, access, Type, extent, label) binding,
constexpr uint32_t kRowBindings[] = {EVERY_BUFFER_ROW(ROW_BINDING)};
#undef ROW_BINDING
constexpr bool bindingsDistinct() {
  for (size_t i = 0; i < std::size(kRowBindings); ++i)
    for (size_t j = i + 1; j < std::size(kRowBindings); ++j)
      if (kRowBindings[i] == kRowBindings[j]) return false;
  return true;
}
static_assert(bindingsDistinct(), "two buffer rows share a binding number");

// The texel rows' elements are whole RGBA32UI texels, as many as the accessors of
// shaders/gpu/texel_rows.glsl fetch.
static_assert(sizeof(shared::BvhNode) == shared::kTexelsPerBvhNode * 16, "BvhNode: whole texels");
static_assert(sizeof(shared::TextureGpu) == sizeof(glm::uvec4), "TextureGpu: stored as one uvec4 (textureFromWords)");
static_assert(sizeof(shared::TriangleGeom) == shared::kTexelsPerTriangleGeom * 16, "TriangleGeom: whole texels");
static_assert(sizeof(shared::TriangleShading) == shared::kTexelsPerTriangleShading * 16, "TriangleShading: whole texels");
static_assert(sizeof(shared::MaterialGpu) == shared::kTexelsPerMaterial * 16, "MaterialGpu: whole texels");
static_assert(sizeof(shared::LightGpu) == shared::kTexelsPerLight * 16, "LightGpu: whole texels");
static_assert(sizeof(shared::EmitterGpu) == shared::kTexelsPerEmitter * 16, "EmitterGpu: whole texels");
static_assert(sizeof(shared::LightBvhNodeGpu) == shared::kTexelsPerLightBvhNode * 16, "LightBvhNodeGpu: whole texels");
static_assert(sizeof(shared::LightSelectionGpu) == shared::kTexelsPerLightSelection * 16, "LightSelectionGpu: whole texels");
static_assert(sizeof(shared::ClusterGpu) == shared::kTexelsPerCluster * 16, "ClusterGpu: whole texels");
static_assert(isTexelBinding(shared::BINDING_BVH_NODES) && isTexelBinding(shared::BINDING_TRIANGLES) &&
                  !isTexelBinding(shared::BINDING_RAY_ORIGIN),
              "the BVH's rows are read as texels, the path state as storage buffers");

}  // namespace
}  // namespace mixtrace
