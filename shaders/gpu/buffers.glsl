// Every buffer of the descriptor set (shaders/shared/bindings.h), the push constants and the
// accessor macros the shared headers use. Included by each wavefront stage.
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require

#include "shared/bindings.h"
#include "shared/cms_layouts.h"
#include "shared/layouts.h"

layout(constant_id = SPEC_HAS_TEXTURES) const bool HAS_TEXTURES = true;
layout(constant_id = SPEC_HAS_AREA_LIGHTS) const bool HAS_AREA_LIGHTS = true;
layout(constant_id = SPEC_HAS_PUNCTUAL_LIGHTS) const bool HAS_PUNCTUAL_LIGHTS = true;
layout(constant_id = SPEC_HAS_METALS) const bool HAS_METALS = true;
layout(constant_id = SPEC_SINGLE_LIGHT) const bool SINGLE_LIGHT = false;

// Push constants, as `pc`: PassConstants unless the pass defines PUSH_CONSTANT_TYPE before
// including this file (the CMS solve pass reads SolveParams).
#ifndef PUSH_CONSTANT_TYPE
#define PUSH_CONSTANT_TYPE PassConstants
#endif
layout(push_constant, scalar) uniform Push { PUSH_CONSTANT_TYPE pc; };

layout(scalar, binding = BINDING_CAMERA) readonly buffer CameraBuf { CameraGpu camera; };
layout(scalar, binding = BINDING_BVH_NODES) readonly buffer NodeBuf { BvhNode bvhNodes[]; };
layout(scalar, binding = BINDING_TRIANGLES) readonly buffer TriBuf { TriangleGeom triangles[]; };
layout(scalar, binding = BINDING_TRIANGLE_SHADING) readonly buffer ShadeBuf { TriangleShading triangleShading[]; };
layout(scalar, binding = BINDING_MATERIALS) readonly buffer MatBuf { MaterialGpu materials[]; };
layout(scalar, binding = BINDING_TEXTURES) readonly buffer TexBuf { TextureGpu textures[]; };
layout(scalar, binding = BINDING_TEXELS) readonly buffer TexelBuf { uint texels[]; };
layout(scalar, binding = BINDING_LIGHTS) readonly buffer LightBuf { LightGpu lights[]; };
layout(scalar, binding = BINDING_EMITTERS) readonly buffer EmitterBuf { EmitterGpu emitters[]; };

layout(scalar, binding = BINDING_RAY_ORIGIN) buffer RayOriginBuf { vec3 rayOrigin[]; };
layout(scalar, binding = BINDING_RAY_DIRECTION) buffer RayDirBuf { vec3 rayDirection[]; };
layout(scalar, binding = BINDING_THROUGHPUT) buffer ThroughputBuf { vec3 throughput[]; };
layout(scalar, binding = BINDING_RADIANCE) buffer RadianceBuf { vec3 radiance[]; };
layout(scalar, binding = BINDING_RNG) buffer RngBuf { uint rngState[]; };
layout(scalar, binding = BINDING_MIS_PDF) buffer MisPdfBuf { float misPdf[]; };
layout(scalar, binding = BINDING_HITS) buffer HitBuf { HitRecord hits[]; };

layout(scalar, binding = BINDING_RAY_QUEUE) buffer RayQueueBuf { uint rayQueue[]; };
layout(scalar, binding = BINDING_SHADOW_QUEUE) buffer ShadowQueueBuf { ShadowRay shadowQueue[]; };
layout(scalar, binding = BINDING_QUEUE_STATE) buffer QueueStateBuf { QueueState queues; };

layout(scalar, binding = BINDING_FILM) buffer FilmBuf { vec3 film[]; };  // [2 * pixel] mean, [2 * pixel + 1] sqrt of the sum of squared deviations (shared/film.h)

// Controlled mixture sampling: per-cell statistics and solutions, flat arrays indexed by the
// functions of shared/cms_layouts.h.
layout(scalar, binding = BINDING_CELL_STATS) buffer CellStatsBuf { float cellStats[]; };
layout(scalar, binding = BINDING_CELL_SAMPLES) buffer CellSamplesBuf { uint cellSamples[]; };
layout(scalar, binding = BINDING_CELL_SOLUTION) buffer CellSolutionBuf { float cellSolution[]; };
layout(scalar, binding = BINDING_CLUSTER_DEFAULTS) readonly buffer ClusterDefaultsBuf { float clusterDefaults[]; };

#define BVH_NODE(i) bvhNodes[i]
#define BVH_TRIANGLE(i) triangles[i]
#define TRIANGLE(i) triangles[i]
#define TRIANGLE_SHADING(i) triangleShading[i]
#define MATERIAL(i) materials[i]
#define TEXTURE(i) textures[i]
#define TEXEL(i) texels[i]
#define LIGHT(i) lights[i]
// A light's cluster and its pmf inside the cluster (docs/estimator.md §2), read only through these.
#define LIGHT_CLUSTER(light) LIGHT(light).cluster
#define LIGHT_CLUSTER_PMF(light) LIGHT(light).clusterPmf
#define EMITTER(i) emitters[i]
