// The row format of the buffer tables (scene_buffers.h, method_buffers.h, path_state.h, cms_state.h, and the rows
// of single passes such as the viewer's display): every buffer a pass can bind is one row
//   BUFFER_<ID>(X) -> X(ID, name, binding, access, Type, extent, label)
// and a pass's interface header lists the rows it reads (shaders/wavefront/*_interface.h). From
// a row come, through the X the user passes:
//   - the binding number, as the constant BINDING_<ID> (below, in C++ and GLSL alike);
//   - the GLSL declaration `Type name[]` (or `Type name` for ONE) at that binding
//     (shaders/gpu/buffers.glsl), so the pass bodies use `name`;
//   - the host's allocation (extent x sizeof(Type) bytes, labelled `label` in error messages) and
//     its binding (host/wavefront/device_buffers.*).
// Binding numbers are one space for all tables: a buffer has one number in every pass that binds
// it (host/vulkan/layout_checks.cpp asserts that no two rows share one). Taken: 0-8 (scene),
// 9-19 (path state, queues, film), 20-29 (CMS), 30 (the viewer's window), 31 (the method's light
// selection), 32 (the method's light BVH), 33 (path state: the MIS normals), 34-47 (the pair table, its solve and tests), 48 (the
// environment), 49 (the AOVs), 50 (second texture coordinates), 51-57 and 60-63, 65 (tests), 58-59 and 64
// (the CMS texel views, shared/cms_state.h CMS_STATE_VIEWS). Each pass's descriptor set
// holds only the rows its interface lists, so the per-stage limit on storage buffers (32 on
// lavapipe) applies to one pass, not to the sum of all.
//
// access: READ_ONLY (declared readonly), READ_WRITE, READ_BACK (read-write, and read by the host
// after a submission: allocated where the host reads it cheaply), TEXELS (read-only, bound as a
// storage texel buffer of RGBA32UI texels, which keep every bit pattern, and read with imageLoad
// through the accessors of gpu/texel_rows.glsl: Type must be a whole number of 16-byte texels;
// lavapipe gathers texels with vector instructions where it loads a storage buffer one lane at a
// time, which made its intersect and shadow passes 17-35 % and its shade pass 21-31 % faster, and
// it loads a storage image's texels inline where it calls a function for each texelFetch of a
// uniform texel buffer, 5-14 % more; benchmarks/README.md, "BVH layout").
// extent (elements): ONE (a single struct), PER_PATH, THREE_PER_PATH (the ray queues: two ping-pong thirds and the shade queue), PER_PIXEL,
// TWO_PER_PIXEL, CELL_SLOTS / CELL_STATS / CELL_SOLUTIONS (the CMS cell table, x the per-cell
// strides of shared/cms_layouts.h), CMS_PATHS / CMS_PIXELS (per path / pixel when the method
// learns, else one: a placeholder), UPLOADED (the host uploads its contents; the size is theirs),
// WINDOW_PIXELS (the viewer's window).
#ifndef MIXTRACE_SHARED_BUFFER_TABLE_H
#define MIXTRACE_SHARED_BUFFER_TABLE_H
#include "shared/dialect.h"

// Whether a row of this access is a storage texel buffer (TEXELS) rather than a storage buffer.
#define BUFFER_IS_TEXELS_READ_ONLY false
#define BUFFER_IS_TEXELS_READ_WRITE false
#define BUFFER_IS_TEXELS_READ_BACK false
#define BUFFER_IS_TEXELS_TEXELS true

// 32-bit words per RGBA32UI texel. A word view (a row of Type float read as texels: word i is
// component i % 4 of texel i / 4, ROW_WORD in gpu/texel_rows.glsl) needs its buffer padded to
// whole texels (host/vulkan/buffer.h wordsInWholeTexels).
SHARED_BEGIN
const uint kWordsPerTexel = 4u;
SHARED_END

// X for a table: declares the row's binding number as BINDING_<ID>.
#define BUFFER_BINDING_CONSTANT(ID, name, binding, access, Type, extent, label) const uint BINDING_##ID = uint(binding);

#endif
