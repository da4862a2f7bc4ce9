#pragma once
// The CPU reference's one binding of the shared headers' accessor macros: every macro reads the
// calling thread's CpuKernelContext (cpu/cpu_kernel_context.h), the scene's arrays through
// scene/shared_scene_access.h and the CMS state through its CpuCmsCells. Include this instead of
// the shared headers. They have internal linkage, so a translation unit that binds the macros
// differently (a test) cannot collide with this one.
#include "cpu/cpu_kernel_context.h"

#define SHARED_SCENE (*::mixtrace::boundCpuKernel().scene)
#define SHARED_LIGHT_SELECTION (*::mixtrace::boundCpuKernel().lightSelection)
#define SHARED_LIGHT_BVH (::mixtrace::boundLightBvh())
#define SHARED_UNIFORM_EMITTERS (::mixtrace::boundCpuKernel().uniformEmitters)
#include "scene/shared_scene_access.h"

#define CELL_KEY_LOAD(slot) (::mixtrace::boundCpuKernel().cms->keyLoad(slot))
#define CELL_KEY_CAS(slot, expected, desired) (::mixtrace::boundCpuKernel().cms->keyCompareSwap(slot, expected, desired))
#define CLUSTER(i) (::mixtrace::boundCpuKernel().cms->cluster(i))
#define CLUSTER_LIGHT(i) (::mixtrace::boundCpuKernel().cms->clusterLight(i))
#define CELL_SOLUTION(i) (::mixtrace::boundCpuKernel().cms->solution(i))
#define CLUSTER_DEFAULT(k) (::mixtrace::boundCpuKernel().cms->clusterDefault(k))
#define FILM_MEAN(i) (::mixtrace::boundCpuKernel().filmMean[i])
// The statistics in double precision (docs/estimator.md §4), added with compare-exchange loops.
#define CMS_STAT_REAL double
#define CMS_ADD_STAT(cell, index, value) (::mixtrace::boundCpuKernel().cms->addStatistic(cell, index, value))

// The per-technique control variate's pair table (shared/cms_pair_terms.h), in double precision too.
#define PAIR_KEY_LOAD(slot) (::mixtrace::boundCpuKernel().cms->pairKeyLoad(slot))
#define PAIR_KEY_CAS(slot, expected, desired) \
  (::mixtrace::boundCpuKernel().cms->pairKeyCompareSwap(slot, expected, desired))
#define PAIR_SLOT_CLAIMED(slot) (::mixtrace::boundCpuKernel().cms->pairSlotClaimed(slot))
#define PAIR_OCCUPIED_COUNT() (::mixtrace::boundCpuKernel().cms->pairOccupiedCount())
#define TECHNIQUE(source) (::mixtrace::boundCpuKernel().cms->technique(source))
#define PAIR_ALPHA(i) (::mixtrace::boundCpuKernel().cms->pairAlpha(i))
#define CMS_ADD_PAIR_STAT(index, value) (::mixtrace::boundCpuKernel().cms->addPairStatistic(index, value))
#define CMS_ADD_PAIR_SAMPLE(slot) (::mixtrace::boundCpuKernel().cms->addPairSample(slot))
#define CMS_COUNT_PAIR(counter) (::mixtrace::boundCpuKernel().cms->countPair(counter))

#include "shared/cms_cells.h"
#include "shared/cms_sampling.h"
#include "shared/cms_vertex_terms.h"
#include "shared/cms_pair_terms.h"
#include "shared/pixel_estimate.h"
