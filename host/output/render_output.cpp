#include "output/render_output.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "output/exr_io.h"
#include "output/png_preview.h"
#include "util/error.h"

namespace mixtrace {

ImageFormat imageFormatOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension == ".exr") return ImageFormat::Exr;
  if (extension == ".png") return ImageFormat::Png;
  if (extension == ".jpg" || extension == ".jpeg") return ImageFormat::Jpeg;
  throw Error("cannot tell the image format of '" + path + "' from its extension" +
              (extension.empty() ? std::string(" (it has none)") : " ('" + extension + "')") +
              ": use .exr (float data, with a PNG preview beside it), .png or .jpg (tonemapped 8-bit)");
}

std::string previewPathFor(const std::string& imagePath, bool png) {
  if (!png || imageFormatOf(imagePath) != ImageFormat::Exr) return "";
  return defaultPreviewPath(imagePath);
}

void writeRenderOutput(const std::string& imagePath, const Image& image, const Image* standardError,
                       const RenderOutputInfo& info, bool png, const std::vector<ExrLayer>& layers) {
  switch (imageFormatOf(imagePath)) {
    case ImageFormat::Png: writePngPreview(imagePath, image); return;
    case ImageFormat::Jpeg: writeJpegPreview(imagePath, image); return;
    case ImageFormat::Exr: break;
  }
  ExrMetadata meta;
  meta.ints["spp"] = info.spp;
  if (info.targetSpp > 0) meta.ints["targetSpp"] = info.targetSpp;
  meta.floats["renderSeconds"] = float(info.seconds);
  meta.strings["method"] = info.method;
  meta.strings["estimator"] = info.estimator.empty() ? info.method : info.estimator;
  meta.strings["scene"] = info.scene;
  meta.strings["renderer"] = std::string("mixtrace ") + MIXTRACE_VERSION;
  if (!info.interruptedBy.empty()) meta.strings["interrupted"] = info.interruptedBy;
  writeExr(imagePath, image, meta, standardError, layers);
  const std::string preview = previewPathFor(imagePath, png);
  if (!preview.empty()) writePngPreview(preview, image);
}

}  // namespace mixtrace
