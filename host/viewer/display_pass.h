#pragma once
// The viewer's display pass (shaders/viewer/display.comp) over one renderer: the film, or a debug
// view of its CMS cells, letterboxed into the viewer's window buffer. It builds its own set of
// what shaders/viewer/display_interface.h lists, from the renderer's buffers (read only) and the
// viewer's window buffer; the renderer knows nothing of it.
#include <vulkan/vulkan.h>

#include "wavefront/wavefront_renderer.h"
#include "viewer/display_interface.h"
#include "vulkan/compute_pass.h"

namespace mixtrace {

class DisplayPass {
 public:
  DisplayPass(VulkanContext& ctx, const WavefrontRenderer& renderer);
  void bindWindow(const Buffer& window);   // the packed 8-bit window pixels it writes
  // The columns [xBegin, xEnd) of the window; the caller orders it against the copy that follows.
  void record(VkCommandBuffer cmd, const shared::DisplayConstants& constants) const;

 private:
  const WavefrontRenderer& renderer_;
  ComputePass pass_;
};

}  // namespace mixtrace
