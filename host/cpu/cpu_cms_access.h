#pragma once
// Lets C++ run shared/cms_cells.h and shared/cms_sampling.h on the CPU reference's CMS state: binds
// their accessor macros to a CpuCmsCells, as scene/shared_scene_access.h binds the scene's. Point
// mixtrace::gCpuCmsCells at the cells before calling into those headers (the renderer does, on
// the thread that starts the workers). Internal linkage of the headers keeps other bindings apart.
#include "cpu/cpu_cms_cells.h"
#include "scene/shared_scene_access.h"

namespace mixtrace {
// The CMS state the shared headers read in this process.
inline CpuCmsCells* gCpuCmsCells = nullptr;
}  // namespace mixtrace

#define CELL_KEY_LOAD(slot) (::mixtrace::gCpuCmsCells->keyLoad(slot))
#define CELL_KEY_CAS(slot, expected, desired) (::mixtrace::gCpuCmsCells->keyCompareSwap(slot, expected, desired))
#define CLUSTER(i) (::mixtrace::gCpuCmsCells->cluster(i))
#define CLUSTER_LIGHT(i) (::mixtrace::gCpuCmsCells->clusterLight(i))
#define CELL_SOLUTION(i) (::mixtrace::gCpuCmsCells->solution(i))
#define CLUSTER_DEFAULT(k) (::mixtrace::gCpuCmsCells->clusterDefault(k))

#include "shared/cms_cells.h"
#include "shared/cms_sampling.h"
