#include "viewer/display_pass.h"

#include <algorithm>

namespace mixtrace {
namespace {

// The display's rows but its own window buffer: what it reads of the renderer.
std::vector<uint32_t> rendererRows() {
  std::vector<uint32_t> rows = BINDINGS_OF(DISPLAY_BUFFERS);
  rows.erase(std::remove(rows.begin(), rows.end(), shared::BINDING_WINDOW), rows.end());
  return rows;
}

}  // namespace

DisplayPass::DisplayPass(VulkanContext& ctx, const WavefrontRenderer& renderer)
    : renderer_(renderer),
      pass_(ctx, "display", BINDINGS_OF(DISPLAY_BUFFERS), sizeof(shared::DisplayConstants), renderer.specialization()) {
  for (uint32_t binding : rendererRows()) pass_.bind(binding, *renderer.buffers().at(binding));
}

void DisplayPass::bindWindow(const Buffer& window) { pass_.bind(shared::BINDING_WINDOW, window); }

void DisplayPass::record(VkCommandBuffer cmd, const shared::DisplayConstants& c) const {
  pass_.dispatch(cmd, &c, sizeof(c), (c.xEnd - c.xBegin + 7) / 8, (c.windowHeight + 7) / 8);
}

}  // namespace mixtrace
