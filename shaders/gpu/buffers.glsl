// The declarations of one pass: the buffers its interface header lists, its push constants and
// the accessor macros the shared headers use. The pass includes its interface header (e.g.
// wavefront/shade_interface.h) and defines, before including this file,
//   PASS_BUFFERS    its list of buffer rows (shared/buffer_table.h), e.g. SHADE_BUFFERS
//   PASS_CONSTANTS  its push-constant struct, read as `pc` (none when undefined)
//   PASS_UNREAD_BUFFERS (optional) the rows that only functions of its headers that it never
//                   calls name: declared so that GLSL compiles those functions; the compiler
//                   drops them and the host does not bind them
// A pass that lists CMS buffers includes gpu/cms_buffers.glsl first (the 64-bit cell keys need
// its extensions). Binding a buffer a pass does not list is not possible: the host builds each
// pass's descriptor set from the same list (host/vulkan/compute_pass.h).
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require

#include "shared/bindings.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/layouts.h"

layout(constant_id = SPEC_HAS_TEXTURES) const bool HAS_TEXTURES = true;
layout(constant_id = SPEC_HAS_AREA_LIGHTS) const bool HAS_AREA_LIGHTS = true;
layout(constant_id = SPEC_HAS_PUNCTUAL_LIGHTS) const bool HAS_PUNCTUAL_LIGHTS = true;
layout(constant_id = SPEC_HAS_METALS) const bool HAS_METALS = true;
layout(constant_id = SPEC_SINGLE_LIGHT) const bool SINGLE_LIGHT = false;
layout(constant_id = SPEC_HAS_ENVIRONMENT) const bool HAS_ENVIRONMENT = true;
layout(constant_id = SPEC_HAS_VERTEX_COLORS) const bool HAS_VERTEX_COLORS = true;
layout(constant_id = SPEC_HAS_ALPHA) const bool HAS_ALPHA = true;
layout(constant_id = SPEC_HAS_NORMAL_MAPS) const bool HAS_NORMAL_MAPS = true;
layout(constant_id = SPEC_HAS_TRANSMISSION) const bool HAS_TRANSMISSION = true;
layout(constant_id = SPEC_HAS_SECOND_UVS) const bool HAS_SECOND_UVS = true;
layout(constant_id = SPEC_LIGHT_SELECTION) const uint LIGHT_SELECTION = kLightSelectPower;

#ifdef PASS_CONSTANTS
layout(push_constant, scalar) uniform Push { PASS_CONSTANTS pc; };
#endif

// One row of a buffer table as a GLSL buffer: `Type name[]`, or `Type name` for a single struct.
#define BUFFER_ACCESS_READ_ONLY readonly
#define BUFFER_ACCESS_READ_WRITE
#define BUFFER_ACCESS_READ_BACK
#define BUFFER_ELEMENTS_ONE
#define BUFFER_ELEMENTS_PER_PATH []
#define BUFFER_ELEMENTS_THREE_PER_PATH []
#define BUFFER_ELEMENTS_SHADOW_SLOTS []
#define BUFFER_ELEMENTS_PER_PIXEL []
#define BUFFER_ELEMENTS_TWO_PER_PIXEL []
#define BUFFER_ELEMENTS_AOV_PIXELS []
#define BUFFER_ELEMENTS_CELL_SLOTS []
#define BUFFER_ELEMENTS_CELL_STATS []
#define BUFFER_ELEMENTS_CELL_SOLUTIONS []
#define BUFFER_ELEMENTS_CELL_SCRATCH []
#define BUFFER_ELEMENTS_PAIR_SLOTS []
#define BUFFER_ELEMENTS_PAIR_STATS []
#define BUFFER_ELEMENTS_PAIR_ALPHAS []
#define BUFFER_ELEMENTS_PAIR_COUNTER_SLOTS []
#define BUFFER_ELEMENTS_PAIR_OCCUPIED_SLOTS []
#define BUFFER_ELEMENTS_DISPATCH_ARGS []
#define BUFFER_ELEMENTS_CMS_PATHS []
#define BUFFER_ELEMENTS_CMS_PIXELS []
#define BUFFER_ELEMENTS_UPLOADED []
#define BUFFER_ELEMENTS_WINDOW_PIXELS []
#define DECLARE_STORAGE_BUFFER(name, bindingNumber, access, Type, extent) \
  layout(scalar, binding = bindingNumber) BUFFER_ACCESS_##access buffer name##Buffer { Type name BUFFER_ELEMENTS_##extent; };
#define DECLARE_BUFFER_READ_ONLY(name, bindingNumber, Type, extent) DECLARE_STORAGE_BUFFER(name, bindingNumber, READ_ONLY, Type, extent)
#define DECLARE_BUFFER_READ_WRITE(name, bindingNumber, Type, extent) DECLARE_STORAGE_BUFFER(name, bindingNumber, READ_WRITE, Type, extent)
#define DECLARE_BUFFER_READ_BACK(name, bindingNumber, Type, extent) DECLARE_STORAGE_BUFFER(name, bindingNumber, READ_BACK, Type, extent)
// A TEXELS row: RGBA32UI texels (its words' bits); the accessors below assemble its Type from them.
#define DECLARE_BUFFER_TEXELS(name, bindingNumber, Type, extent) layout(rgba32ui, binding = bindingNumber) readonly uniform uimageBuffer name;
#define DECLARE_BUFFER(ID, name, bindingNumber, access, Type, extent, label) \
  DECLARE_BUFFER_##access(name, bindingNumber, Type, extent)

PASS_BUFFERS(DECLARE_BUFFER)
#ifdef PASS_UNREAD_BUFFERS
PASS_UNREAD_BUFFERS(DECLARE_BUFFER)
#endif

#include "gpu/texel_rows.glsl"
#define BVH_TRIANGLE(i) TRIANGLE(i)
#define TRIANGLE_UV2(i) triangleUv2[i]
#define TEXTURE(i) textureFromWords(imageLoad(textures, int(i)))
#define TEXEL(i) ROW_UINT(texels, i)
#define ENV_DATA(i) ROW_WORD(environment, i)
// How the method picks the scene's lights (shared/method_buffers.h); a light's cluster and its pmf
// inside the cluster (docs/estimator.md §2) are read only through these.
// (A TEXELS row: one texel per light, gpu/texel_rows.glsl; each accessor loads the word it names.)
#define LIGHT_SELECT_PMF(i) uintBitsToFloat(ROW_TEXEL(lightSelection, kTexelsPerLightSelection, i, 0u).x)
#define LIGHT_SELECT_CDF(i) uintBitsToFloat(ROW_TEXEL(lightSelection, kTexelsPerLightSelection, i, 0u).y)
#define LIGHT_CLUSTER(light) ROW_TEXEL(lightSelection, kTexelsPerLightSelection, light, 0u).z
#define LIGHT_CLUSTER_PMF(light) uintBitsToFloat(ROW_TEXEL(lightSelection, kTexelsPerLightSelection, light, 0u).w)
