// What the controlled-mixture-sampling variants of the passes need before their buffers are
// declared (gpu/buffers.glsl, from the rows of shared/cms_state.h): the 64-bit cell keys'
// extensions, the CMS specialization constants and the accessor macros of shared/cms_cells.h and
// shared/cms_sampling.h. Included before gpu/buffers.glsl by the passes that list CMS buffers.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#ifdef CMS_FLOAT_ATOMICS
#extension GL_EXT_shader_atomic_float : require
#endif

#include "shared/bindings.h"

layout(constant_id = SPEC_CMS_SELECTION) const bool CMS_SELECTION = false;
layout(constant_id = SPEC_CMS_CONTROL_VARIATE) const bool CMS_CONTROL_VARIATE = false;
layout(constant_id = SPEC_CMS_RELATIVE_WEIGHT) const bool CMS_RELATIVE_WEIGHT = true;
// The per-triangle control variate (shared/cms_pair_terms.h): false folds its code away at pipeline
// creation, so the other methods' pipelines carry none of it (their pair rows are placeholders).
layout(constant_id = SPEC_CMS_PAIR_TECHNIQUES) const bool CMS_PAIR_TECHNIQUES = false;

#define CELL_KEY_LOAD(slot) cellKeys[slot]
#define CELL_KEY_CAS(slot, expected, desired) atomicCompSwap(cellKeys[slot], expected, desired)
#define CLUSTER(i) clusterFromTexel(ROW_TEXEL(clusters, kTexelsPerCluster, i, 0u))
#define CLUSTER_LIGHT(i) clusterLights[i]
// The passes that only read the solutions, pair coefficients and default selection (shade, shadow,
// fused) list their views as texels (shared/cms_state.h CMS_STATE_VIEWS) and define
// PASS_READS_SOLUTION_VIEWS.
#ifdef PASS_READS_SOLUTION_VIEWS
#define CELL_SOLUTION(i) ROW_WORD(cellSolutionTexels, i)
#define PAIR_ALPHA(i) ROW_WORD(pairAlphaTexels, i)
#define CLUSTER_DEFAULT(k) ROW_WORD(clusterDefaultsTexels, k)
#else
#define CELL_SOLUTION(i) cellSolution[i]
#define PAIR_ALPHA(i) pairAlpha[i]
#define CLUSTER_DEFAULT(k) clusterDefaults[k]
#endif
#include "gpu/pair_table_access.glsl"
#define TECHNIQUE(source) techniques[source]
