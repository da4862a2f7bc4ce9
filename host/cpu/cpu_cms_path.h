#pragma once
// One path of the CPU reference with controlled mixture sampling (methods learned, cv, cms;
// docs/estimator.md): at every vertex the light comes from a cluster chosen by the vertex's cell,
// p_eff = c_k p_k + p_B, every sample adds its statistics to the cell and, with the control
// variate, the vertex pays + sum(alpha) - g(z)/p_eff(z) for both samples. Its terms are those of
// shared/cms_vertex_terms.h that shaders/wavefront/shade.comp and shadow.comp call, paid in one loop, drawing the same random
// numbers in the same order (so with the same seed and the same cell solutions the two backends
// trace the same paths).
#include <cstdint>

#include <glm/glm.hpp>

#include "cpu/cpu_cms_cells.h"
#include "backend/renderer.h"

namespace mixtrace {

struct CmsPathContext {
  CpuCmsCells* cells = nullptr;   // also the one the calling thread's CpuKernelContext holds
  uint32_t maxDepth = 5;
  uint32_t lightCount = 0;
  uint32_t pixel = 0;             // for the relative statistics weight
};

// The radiance of the path from `origin` along `direction`; `rng` continues the camera sample's
// random numbers. Runs inside a CpuKernelBinding of the scene and these cells (cpu/cpu_kernel_context.h).
glm::vec3 traceCmsPath(glm::vec3 origin, glm::vec3 direction, uint32_t& rng, const CmsPathContext& ctx,
                       RenderCounters& counters);

}  // namespace mixtrace
