#pragma once
// What the shared shader headers read when the CPU reference runs them: the scene, the method's
// light selection, the CMS state and (while the pixel estimate is refreshed) the film's running
// means, as one object. Each thread that calls into the headers binds its context first (CpuKernelBinding, for a scope): the
// accessor macros of cpu/cpu_kernel_access.h read the calling thread's context, so two renderers
// of different scenes can render at once on different threads. The GPU binds the same macros to
// its buffers (shaders/gpu/buffers.glsl, cms_buffers.glsl).
#include <vector>

#include <glm/glm.hpp>

#include "cpu/cpu_cms_cells.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"

namespace mixtrace {

struct CpuKernelContext {
  const PreparedScene* scene = nullptr;
  const std::vector<shared::LightSelectionGpu>* lightSelection = nullptr;   // the method's, per light
  const std::vector<shared::LightBvhNodeGpu>* lightBvh = nullptr;   // the method's light BVH (empty: none)
  bool uniformEmitters = false;            // the method picks a light's triangle uniformly
  CpuCmsCells* cms = nullptr;              // the CMS methods' cells; null for the pt-* methods
  const glm::vec3* filmMean = nullptr;     // the running means, per pixel (pixel estimate only)
};

namespace cpu_kernel_detail {
// The calling thread's context (constant-initialised, so reading it costs one thread-local load).
inline thread_local const CpuKernelContext* tBound = nullptr;
}  // namespace cpu_kernel_detail

// The context bound on the calling thread; only valid inside a CpuKernelBinding.
inline const CpuKernelContext& boundCpuKernel() { return *cpu_kernel_detail::tBound; }

// The bound context's light BVH; empty (the table's selection) where the context names none.
inline const std::vector<shared::LightBvhNodeGpu>& boundLightBvh() {
  static const std::vector<shared::LightBvhNodeGpu> none;
  const auto* bvh = boundCpuKernel().lightBvh;
  return bvh ? *bvh : none;
}

// Binds `context` on the calling thread for this object's lifetime (restoring what was bound
// before, so bindings nest). The context must outlive the binding.
class CpuKernelBinding {
 public:
  explicit CpuKernelBinding(const CpuKernelContext& context) : previous_(cpu_kernel_detail::tBound) {
    cpu_kernel_detail::tBound = &context;
  }
  ~CpuKernelBinding() { cpu_kernel_detail::tBound = previous_; }
  CpuKernelBinding(const CpuKernelBinding&) = delete;
  CpuKernelBinding& operator=(const CpuKernelBinding&) = delete;

 private:
  const CpuKernelContext* previous_;
};

}  // namespace mixtrace
