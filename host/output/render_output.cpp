#include "output/render_output.h"

#include "output/exr_io.h"
#include "output/png_preview.h"

namespace mixtrace {

void writeRenderOutput(const std::string& exrPath, const Image& image, const Image* variance,
                       const RenderOutputInfo& info, bool png) {
  ExrMetadata meta;
  meta.ints["spp"] = info.spp;
  meta.floats["renderSeconds"] = float(info.seconds);
  meta.strings["method"] = info.method;
  meta.strings["scene"] = info.scene;
  meta.strings["renderer"] = std::string("mixtrace ") + MIXTRACE_VERSION;
  writeExr(exrPath, image, meta, variance);
  if (png) writePngPreview(defaultPreviewPath(exrPath), image);
}

}  // namespace mixtrace
