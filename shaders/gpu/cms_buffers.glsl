// The buffers only the controlled-mixture-sampling variants of the stages read: the cell table,
// the clusters and the per-path state of the previous vertex's BSDF sample (whose control-variate
// and statistics terms are paid at the next vertex, once its hit is known).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#ifdef CMS_FLOAT_ATOMICS
#extension GL_EXT_shader_atomic_float : require
#endif

#include "shared/cluster_layout.h"

layout(scalar, binding = BINDING_CELL_KEYS) buffer CellKeyBuf { uint64_t cellKeys[]; };
layout(scalar, binding = BINDING_CLUSTERS) readonly buffer ClusterBuf { ClusterGpu clusters[]; };
layout(scalar, binding = BINDING_CLUSTER_LIGHTS) readonly buffer ClusterLightBuf { ClusterLightGpu clusterLights[]; };
layout(scalar, binding = BINDING_CV_STATE) buffer CvStateBuf { CvPathState cvState[]; };
layout(scalar, binding = BINDING_PIXEL_ESTIMATE) buffer PixelEstimateBuf { vec3 pixelEstimate[]; };
layout(scalar, binding = BINDING_FIRST_CELL) buffer FirstCellBuf { uint firstCell[]; };

layout(constant_id = SPEC_CMS_SELECTION) const bool CMS_SELECTION = false;
layout(constant_id = SPEC_CMS_CONTROL_VARIATE) const bool CMS_CONTROL_VARIATE = false;
layout(constant_id = SPEC_CMS_RELATIVE_WEIGHT) const bool CMS_RELATIVE_WEIGHT = true;

#define CELL_KEY_LOAD(slot) cellKeys[slot]
#define CELL_KEY_CAS(slot, expected, desired) atomicCompSwap(cellKeys[slot], expected, desired)
#define CLUSTER(i) clusters[i]
#define CLUSTER_LIGHT(i) clusterLights[i]
#define CELL_SOLUTION(i) cellSolution[i]
#define CLUSTER_DEFAULT(k) clusterDefaults[k]
