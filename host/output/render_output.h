#pragma once
// What a finished (or interrupted) render writes, for `render` and the viewer's save key alike.
// The format follows the extension of the output's name: .exr is the result (linear float RGB,
// optionally the standard error of the mean, with spp, time, method, estimator and scene in its header)
// with, unless disabled, the 8-bit sRGB PNG preview beside it; .png and .jpg/.jpeg are the
// tonemapped image only. Every file is written atomically (output/atomic_file.h).
#include <string>

#include <vector>

#include "output/exr_io.h"
#include "output/image.h"

namespace mixtrace {

enum class ImageFormat { Exr, Png, Jpeg };

// The format `path`'s extension names (case-insensitive). Throws mixtrace::Error for any other
// extension, or none, so that a misspelt name is refused before rendering, not after.
ImageFormat imageFormatOf(const std::string& path);

// The PNG preview written beside `imagePath`: "" when there is none (not an EXR, or !png).
std::string previewPathFor(const std::string& imagePath, bool png);

struct RenderOutputInfo {
  std::string method;        // as asked for (--method)
  std::string estimator;     // what ran: the method, or pt-power where cms reduces to it
  std::string scene;
  int spp = 0;               // samples per pixel in the image
  int targetSpp = 0;         // what was asked for; 0 when open-ended (--time, the viewer)
  double seconds = 0.0;
  std::string interruptedBy; // "SIGINT" or "SIGTERM" when the render stopped early; else ""
};

// `standardError` goes into an EXR only (the caller refuses --variance with other formats).
// `layers`: more EXR channels (the AOVs), EXR only as well.
void writeRenderOutput(const std::string& imagePath, const Image& image, const Image* standardError,
                       const RenderOutputInfo& info, bool png, const std::vector<ExrLayer>& layers = {});

}  // namespace mixtrace
