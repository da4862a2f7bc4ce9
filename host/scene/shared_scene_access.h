#pragma once
// Lets C++ run the shared shader headers (lights.h, surface.h, bvh_traverse.h, ...) on a
// PreparedScene: binds their buffer-access macros to the scene's arrays and turns the feature
// switches on (the CPU needs no specialisation), but for the two read at every hit candidate or
// hit (alpha, vertex colours), which follow the scene. Include this instead of those headers, after
// defining SHARED_SCENE as an expression naming the scene (a `const PreparedScene&`) and
// SHARED_LIGHT_SELECTION as one naming the method's selection table (a `const
// std::vector<LightSelectionGpu>&`, one entry per light, scene/light_selection.h): no process
// global, so each includer decides where they come from (the CPU reference: the calling thread's
// context, cpu/cpu_kernel_access.h). The headers have internal linkage, so a translation unit that
// binds the macros differently cannot collide with this one.
#include <vector>

#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
#include "shared/layouts.h"

#if !defined(SHARED_SCENE) || !defined(SHARED_LIGHT_SELECTION)
#error "define SHARED_SCENE (the PreparedScene) and SHARED_LIGHT_SELECTION (the method's table) before including scene/shared_scene_access.h"
#endif

#define BVH_NODE(i) (SHARED_SCENE.bvh.nodes[i])
#define BVH_TRIANGLE(i) (SHARED_SCENE.bvh.triangles[i])
#define TRIANGLE(i) (SHARED_SCENE.bvh.triangles[i])
#define TRIANGLE_SHADING(i) (SHARED_SCENE.shading[i])
#define TRIANGLE_UV2(i) (SHARED_SCENE.secondUvs[i])
#define MATERIAL(i) (SHARED_SCENE.scene.materials[i])
#define TEXTURE(i) (SHARED_SCENE.textures[i])
#define TEXEL(i) (SHARED_SCENE.texels[i])
#define LIGHT(i) (SHARED_SCENE.lights.lights[i])
#define EMITTER(i) (SHARED_SCENE.lights.emitters[i])
#define ENV_DATA(i) (SHARED_SCENE.environment[i])
// How the method picks the scene's lights; a light's cluster and its pmf inside the cluster
// (docs/estimator.md §2) are read only through these.
#define LIGHT_SELECT_PMF(i) (SHARED_LIGHT_SELECTION[i].pmf)
#define LIGHT_SELECT_CDF(i) (SHARED_LIGHT_SELECTION[i].cdf)
#define LIGHT_CLUSTER(light) (SHARED_LIGHT_SELECTION[light].cluster)
#define LIGHT_CLUSTER_PMF(light) (SHARED_LIGHT_SELECTION[light].clusterPmf)
// Whether the method picks the triangle inside a light uniformly (SHARED_UNIFORM_EMITTERS: a bool
// expression, false where the includer does not say).
#ifdef SHARED_UNIFORM_EMITTERS
#define EMITTERS_UNIFORM (SHARED_UNIFORM_EMITTERS)
#else
#define EMITTERS_UNIFORM false
#endif
// The method's light BVH (optional: SHARED_LIGHT_BVH names a `const
// std::vector<LightBvhNodeGpu>&`, empty where the method picks lights by the table).
#ifdef SHARED_LIGHT_BVH
#define LIGHT_BVH(i) (SHARED_LIGHT_BVH[i])
#define LIGHT_SELECT_BVH (!SHARED_LIGHT_BVH.empty())
#endif
#define HAS_TEXTURES true
#define HAS_AREA_LIGHTS true
#define HAS_PUNCTUAL_LIGHTS true
#define HAS_METALS true
#define SINGLE_LIGHT false
#define HAS_ENVIRONMENT true
// Read per hit candidate and per hit: decided by the scene at run time, so a scene without them
// pays one branch (the GPU folds them away as specialization constants).
#define HAS_VERTEX_COLORS (SHARED_SCENE.features.vertexColors)
#define HAS_ALPHA (SHARED_SCENE.features.alpha)
#define HAS_NORMAL_MAPS (SHARED_SCENE.features.normalMaps)
#define HAS_TRANSMISSION (SHARED_SCENE.features.transmission)
#define HAS_SECOND_UVS (SHARED_SCENE.features.secondUvs)

#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/lights.h"
#include "shared/surface.h"
