#pragma once
// Lets C++ run the shared shader headers (lights.h, surface.h, bvh_traverse.h, ...) on a
// PreparedScene: binds their buffer-access macros to the scene's arrays and turns every feature
// switch on (the CPU needs no specialisation). Include this instead of those headers, and point
// mixtrace::gSharedScene at the scene and mixtrace::gLightSelection at the method's selection
// table (one LightSelectionGpu per light, scene/light_selection.h) first. The headers have
// internal linkage, so a translation unit that binds the macros differently cannot collide with
// this one.
#include <vector>

#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
#include "shared/layouts.h"

namespace mixtrace {
// The scene the shared headers read in this process (set before calling into them).
inline const PreparedScene* gSharedScene = nullptr;
// How the method picks the scene's lights, read by the same headers (LIGHT_SELECT_*, LIGHT_CLUSTER*).
inline const std::vector<shared::LightSelectionGpu>* gLightSelection = nullptr;
}  // namespace mixtrace

#define BVH_NODE(i) (::mixtrace::gSharedScene->bvh.nodes[i])
#define BVH_TRIANGLE(i) (::mixtrace::gSharedScene->bvh.triangles[i])
#define TRIANGLE(i) (::mixtrace::gSharedScene->bvh.triangles[i])
#define TRIANGLE_SHADING(i) (::mixtrace::gSharedScene->shading[i])
#define MATERIAL(i) (::mixtrace::gSharedScene->scene.materials[i])
#define TEXTURE(i) (::mixtrace::gSharedScene->textures[i])
#define TEXEL(i) (::mixtrace::gSharedScene->texels[i])
#define LIGHT(i) (::mixtrace::gSharedScene->lights.lights[i])
#define EMITTER(i) (::mixtrace::gSharedScene->lights.emitters[i])
#define LIGHT_SELECT_PMF(i) ((*::mixtrace::gLightSelection)[i].pmf)
#define LIGHT_SELECT_CDF(i) ((*::mixtrace::gLightSelection)[i].cdf)
#define LIGHT_CLUSTER(i) ((*::mixtrace::gLightSelection)[i].cluster)
#define LIGHT_CLUSTER_PMF(i) ((*::mixtrace::gLightSelection)[i].clusterPmf)
#define HAS_TEXTURES true
#define HAS_AREA_LIGHTS true
#define HAS_PUNCTUAL_LIGHTS true
#define HAS_METALS true
#define SINGLE_LIGHT false

#include "shared/bvh_traverse.h"
#include "shared/lights.h"
#include "shared/surface.h"
