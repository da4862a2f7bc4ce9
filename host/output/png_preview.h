#pragma once
// An 8-bit sRGB PNG next to the EXR, for a quick look; the EXR stays the result. (Or, for
// --out FILE.png/.jpg, the only output.) Files are written atomically (output/atomic_file.h).
#include <string>
#include <vector>

#include "output/image.h"

namespace mixtrace {

// Scales linear values by `exposure`, clamps to [0, 1], applies the exact piecewise sRGB curve
// and rounds to 8 bits. Non-finite input values (NaN, +-Inf) become black, so a broken pixel
// is visible rather than written as garbage. Throws mixtrace::Error when the file cannot be written.
void writePngPreview(const std::string& path, const Image& image, float exposure = 1.0f);

// The same tonemapping as a JPEG file (quality kJpegQuality), for --out FILE.jpg.
constexpr int kJpegQuality = 95;
void writeJpegPreview(const std::string& path, const Image& image, float exposure = 1.0f);

// 8-bit sRGB bytes as they are (the viewer's screenshots), 3 per pixel, top row first.
void writePng8(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

// `exrPath` with its extension replaced by .png (appended when it has none).
std::string defaultPreviewPath(const std::string& exrPath);

// The 8-bit value writePngPreview stores for one linear channel value (exposed for tests).
unsigned char linearToSrgb8(float linear, float exposure = 1.0f);

}  // namespace mixtrace
