#include "wavefront/device_buffers.h"

#include "shared/aov_layout.h"
#include "shared/cms_pair_state.h"
#include "shared/cms_state.h"
#include "shared/path_state.h"
#include "util/error.h"

namespace mixtrace {
namespace {

enum class Extent { ONE, PER_PATH, THREE_PER_PATH, SHADOW_SLOTS, PER_PIXEL, TWO_PER_PIXEL, CELL_SLOTS, CELL_STATS, CELL_SOLUTIONS,
                    PAIR_SLOTS, PAIR_STATS, PAIR_ALPHAS, PAIR_COUNTER_SLOTS, PAIR_OCCUPIED_SLOTS, CMS_PATHS, CMS_PIXELS, UPLOADED,
                    WINDOW_PIXELS, AOV_PIXELS };
enum class Access { READ_ONLY, READ_WRITE, READ_BACK, TEXELS };

size_t elements(Extent extent, const BufferExtents& e) {
  const size_t pixels = size_t(e.width) * e.height;
  switch (extent) {
    case Extent::ONE: return 1;
    case Extent::PER_PATH: return e.paths;
    case Extent::THREE_PER_PATH: return 3 * size_t(e.paths);
    case Extent::SHADOW_SLOTS: return (e.pairSlots > 1 ? 2 : 1) * size_t(e.paths);
    case Extent::PER_PIXEL: return pixels;
    case Extent::TWO_PER_PIXEL: return 2 * pixels;
    case Extent::CELL_SLOTS: return e.cellSlots;
    case Extent::CELL_STATS: return size_t(e.cellSlots) * shared::cellStatsStride(e.clusters);
    // Whole RGBA32UI texels: the shading passes read the solutions as texels too (shared/cms_state.h).
    case Extent::CELL_SOLUTIONS: return wordsInWholeTexels(size_t(e.cellSlots) * shared::cellSolutionStride(e.clusters));
    case Extent::PAIR_SLOTS: return e.pairSlots;
    case Extent::PAIR_STATS: return size_t(e.pairSlots) * shared::kPairStatsStride;
    case Extent::PAIR_ALPHAS: return size_t(e.pairSlots) * shared::kPairAlphaStride;
    case Extent::PAIR_COUNTER_SLOTS: return shared::kPairCounterSlots;
    case Extent::PAIR_OCCUPIED_SLOTS: return size_t(e.pairSlots) + shared::kPairOccupiedFirst;
    case Extent::CMS_PATHS: return e.cms ? e.paths : 1;
    case Extent::CMS_PIXELS: return e.cms ? pixels : 1;
    case Extent::AOV_PIXELS: return e.aovs ? shared::kAovStride * pixels : 1;
    case Extent::UPLOADED: case Extent::WINDOW_PIXELS: break;
  }
  throw Error("internal: a buffer the renderer does not allocate");
}

bool perPixel(Extent extent) {
  return extent == Extent::PER_PIXEL || extent == Extent::TWO_PER_PIXEL || extent == Extent::AOV_PIXELS;
}

}  // namespace

DeviceBuffers::DeviceBuffers(VulkanContext& ctx, const BufferExtents& e) {
  const std::string imageSize = " (" + std::to_string(e.width) + "x" + std::to_string(e.height) + ")";
  // One allocation per row that the renderer sizes; per-pixel buffers name the image size in
  // their error messages.
  auto allocate = [&](uint32_t binding, Extent extent, size_t elementBytes, Access access, const char* label) {
    if (extent == Extent::UPLOADED) return;
    buffers_.emplace(binding, Buffer(ctx, elements(extent, e) * elementBytes,
                                     std::string(label) + (perPixel(extent) ? imageSize : ""), access == Access::READ_BACK));
  };
  using namespace shared;
#define ALLOCATE_ROW(ID, name, binding, access, Type, extent, label) \
  allocate(BINDING_##ID, Extent::extent, sizeof(Type), Access::access, label);
  PATH_STATE_BUFFERS(ALLOCATE_ROW)
  CMS_STATE_BUFFERS(ALLOCATE_ROW)
  CMS_PAIR_BUFFERS(ALLOCATE_ROW)
#undef ALLOCATE_ROW
}

void DeviceBuffers::add(uint32_t binding, Buffer buffer) { buffers_.insert_or_assign(binding, std::move(buffer)); }

const Buffer& DeviceBuffers::operator[](uint32_t binding) const {
  const auto found = buffers_.find(binding);
  if (found == buffers_.end()) throw Error("internal: no buffer at binding " + std::to_string(binding));
  return found->second;
}

BufferBindings DeviceBuffers::bindings(const BufferBindings& others) const {
  BufferBindings all = others;
  for (const auto& [binding, buffer] : buffers_) all[binding] = &buffer;
  // The views (shared/cms_state.h CMS_STATE_VIEWS, shared/cms_pair_state.h CMS_PAIR_VIEWS): the
  // viewed row's buffer, bound as texels.
#define BIND_VIEW(VIEW, VIEWED) all[shared::BINDING_##VIEW] = &(*this)[shared::BINDING_##VIEWED];
  CMS_STATE_VIEWED(BIND_VIEW)
  CMS_PAIR_VIEWED(BIND_VIEW)
#undef BIND_VIEW
  return all;
}

}  // namespace mixtrace
