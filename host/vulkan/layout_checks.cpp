// Compile-time contracts of the host/GPU boundary: every struct the shaders read from a buffer or
// a push-constant block has, in C++, the size and member offsets the scalar block layout gives it
// in GLSL (host/vulkan/gpu_layout_table.inc derives them), and every push-constant block fits the
// range the pipeline layout declares and the range every Vulkan device guarantees. A layout
// change that breaks one of them fails the build here, not as a wrong image.
// tests/unit/layout_contract_test.cpp checks the other half: that the compiled shaders (the
// embedded SPIR-V) see the same offsets.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/display.h"
#include "shared/layouts.h"

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

// Push constants. Every pass, the solve and the viewer's display pass share one pipeline layout,
// whose single range is sizeof(shared::PassConstants) bytes (host/render/wavefront_renderer.cpp
// creates the DescriptorSet with it); a pass pushes its own struct into the start of that range.
constexpr size_t kPushConstantRangeBytes = sizeof(shared::PassConstants);
// VkPhysicalDeviceLimits::maxPushConstantsSize is at least 128 on every Vulkan device.
constexpr size_t kGuaranteedPushConstantBytes = 128;

static_assert(kPushConstantRangeBytes <= kGuaranteedPushConstantBytes,
              "the push-constant range must fit every device's guaranteed 128 bytes");
static_assert(kPushConstantRangeBytes % 4 == 0, "a push-constant range's size is a multiple of 4");
static_assert(sizeof(shared::PassConstants) <= kPushConstantRangeBytes, "PassConstants must fit the range");
static_assert(sizeof(shared::SolveParams) <= kPushConstantRangeBytes, "SolveParams must fit the range");
static_assert(sizeof(shared::DisplayConstants) <= kPushConstantRangeBytes, "DisplayConstants must fit the range");

}  // namespace
}  // namespace mixtrace
