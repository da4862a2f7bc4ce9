#pragma once
// What a finished render writes, for `render` and the viewer's save key alike: the EXR (linear
// float RGB, optionally the variance of the mean, with spp, time, method and scene in its header)
// and, next to it, the 8-bit sRGB PNG preview.
#include <string>

#include "output/image.h"

namespace mixtrace {

struct RenderOutputInfo {
  std::string method;
  std::string scene;
  int spp = 0;
  double seconds = 0.0;
};

void writeRenderOutput(const std::string& exrPath, const Image& image, const Image* variance,
                       const RenderOutputInfo& info, bool png);

}  // namespace mixtrace
