#include "output/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <exception>
#include <set>

#include <sys/stat.h>

#include "output/atomic_file.h"
#include "util/error.h"

namespace mixtrace {
namespace {

const char* const kColorChannels[3] = {"R", "G", "B"};
// The uncertainty of each pixel is stored as the standard error of its mean: a variance (its
// square) overflows float where the image exceeds ~1e19 and underflows below ~1e-19
// (shared/film.h). Files of earlier versions hold the variance of the mean instead; readExr
// converts those.
const char* const kStandardErrorChannels[3] = {"standardError.R", "standardError.G", "standardError.B"};
const char* const kLegacyVarianceChannels[3] = {"variance.R", "variance.G", "variance.B"};

int channelsPresent(const Imf::ChannelList& channels, const char* const names[3]) {
  int present = 0;
  for (int c = 0; c < 3; ++c) present += channels.findChannel(names[c]) != nullptr;
  return present;
}

// Attributes OpenEXR itself manages; they describe the file, not the render, so readExr leaves
// them out of ExrMetadata and writeExr refuses to overwrite them.
const std::set<std::string> kStructuralAttributes = {
    "channels",          "compression",        "dataWindow", "displayWindow", "lineOrder",
    "pixelAspectRatio",  "screenWindowCenter", "screenWindowWidth", "tiles", "type",
    "name",              "version",            "chunkCount",
};

// OpenEXR messages sometimes span lines; Error promises one.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && (text.back() == ' ' || text.back() == '.')) text.pop_back();
  return text;
}

void checkImageSize(const Image& image, const std::string& what) {
  if (image.width <= 0 || image.height <= 0)
    throw Error("cannot write an empty " + what + " (" + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ")");
  if (image.rgb.size() != image.pixelCount() * 3)
    throw Error(what + " has " + std::to_string(image.rgb.size()) + " floats, expected " +
                std::to_string(image.pixelCount() * 3));
}

// Describes `image` as three interleaved FLOAT slices. `originX/Y` is the data window's corner:
// OpenEXR addresses pixels by absolute coordinates, so the base pointer is shifted back by it.
// Channel c of `names` (at most 3) is component c of the image's pixels.
void addSlices(Imf::FrameBuffer& frameBuffer, const std::vector<std::string>& names, Image& image, int originX,
               int originY) {
  const size_t xStride = 3 * sizeof(float);
  const size_t yStride = xStride * static_cast<size_t>(image.width);
  char* base = reinterpret_cast<char*>(image.rgb.data()) - static_cast<ptrdiff_t>(originX) * xStride -
               static_cast<ptrdiff_t>(originY) * yStride;
  for (size_t c = 0; c < names.size() && c < 3; ++c)
    frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride, 1, 1, 0.0));
}

void addSlices(Imf::FrameBuffer& frameBuffer, const char* const names[3], Image& image, int originX, int originY) {
  addSlices(frameBuffer, std::vector<std::string>(names, names + 3), image, originX, originY);
}

}  // namespace

void writeExr(const std::string& path, const Image& image, const ExrMetadata& meta, const Image* standardError,
              const std::vector<ExrLayer>& layers) {
  checkImageSize(image, "image");
  if (standardError) {
    checkImageSize(*standardError, "variance (standard error) image");
    if (standardError->width != image.width || standardError->height != image.height)
      throw Error("variance (standard error) image is " + std::to_string(standardError->width) + "x" +
                  std::to_string(standardError->height) + " but the image is " + std::to_string(image.width) + "x" +
                  std::to_string(image.height));
  }

  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;  // lossless: the values feed statistical tests
  const auto checkName = [&](const std::string& name) {
    if (name.empty() || kStructuralAttributes.count(name) || header.find(name) != header.end())
      throw Error("EXR attribute name '" + name + "' is empty or reserved");
  };
  for (const auto& [name, value] : meta.strings) {
    checkName(name);
    header.insert(name, Imf::StringAttribute(value));
  }
  for (const auto& [name, value] : meta.ints) {
    checkName(name);
    header.insert(name, Imf::IntAttribute(value));
  }
  for (const auto& [name, value] : meta.floats) {
    checkName(name);
    header.insert(name, Imf::FloatAttribute(value));
  }

  // Slices need mutable pointers even for writing; OpenEXR only reads through them here.
  Imf::FrameBuffer frameBuffer;
  for (const char* name : kColorChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  addSlices(frameBuffer, kColorChannels, const_cast<Image&>(image), 0, 0);
  if (standardError) {
    for (const char* name : kStandardErrorChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    addSlices(frameBuffer, kStandardErrorChannels, const_cast<Image&>(*standardError), 0, 0);
  }
  for (const ExrLayer& layer : layers) {
    checkImageSize(*layer.image, "layer " + layer.names.at(0));
    if (layer.image->width != image.width || layer.image->height != image.height || layer.names.size() > 3)
      throw Error("internal: EXR layer " + layer.names.at(0) + " does not fit the image");
    for (const std::string& name : layer.names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    addSlices(frameBuffer, layer.names, const_cast<Image&>(*layer.image), 0, 0);
  }

  // To a temporary file, renamed when complete: an interrupted write leaves no truncated EXR.
  writeFileAtomically(path, [&](const std::string& temporaryPath) {
    try {
      Imf::OutputFile file(temporaryPath.c_str(), header);
      file.setFrameBuffer(frameBuffer);
      file.writePixels(image.height);
    } catch (const std::exception& e) {
      throw Error("cannot write EXR '" + path + "': " + oneLine(e.what()));
    }
  });
}

namespace {

// What readExr accepts before allocating: the header's data window is the file's claim, and a
// few hundred bytes can claim gigabytes. The largest image render writes is 16384 x 16384
// (--width/--height); and no EXR compression packs float pixels tighter than deflate's
// 1032:1 (PXR24 with its 4:3 on top), so a window needing more than kMaxExrExpansion times the
// file's size cannot be backed by it.
constexpr int64_t kMaxExrSide = 16384;
constexpr int64_t kMaxExrExpansion = 2048;

// The file must be a regular file (a FIFO would block, a device would never end).
int64_t regularFileSize(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw Error("cannot read EXR '" + path + "': " + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw Error("cannot read EXR '" + path + "': not a regular file");
  return int64_t(info.st_size);
}

void checkDataWindow(const std::string& path, const Imath::Box2i& window, int channelCount, int64_t fileSize) {
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) throw Error("EXR '" + path + "' has an empty data window");
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width > kMaxExrSide || height > kMaxExrSide)
    throw Error("EXR '" + path + "' claims " + size + " pixels, more than " + std::to_string(kMaxExrSide) +
                " on a side");
  const int64_t bytes = width * height * channelCount * int64_t(sizeof(float));
  if (bytes / kMaxExrExpansion > fileSize)
    throw Error("EXR '" + path + "' claims " + size + " pixels, more than its " + std::to_string(fileSize) +
                " bytes can hold");
}

}  // namespace

Image readExr(const std::string& path, ExrMetadata* meta, Image* standardError) {
  const int64_t fileSize = regularFileSize(path);
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dataWindow = header.dataWindow();
    checkDataWindow(path, dataWindow, 3, fileSize);
    const int width = dataWindow.max.x - dataWindow.min.x + 1;
    const int height = dataWindow.max.y - dataWindow.min.y + 1;

    const Imf::ChannelList& channels = header.channels();
    for (const char* name : kColorChannels)
      if (!channels.findChannel(name)) throw Error("EXR '" + path + "' has no " + name + " channel");

    Image image(width, height);
    Imf::FrameBuffer frameBuffer;
    addSlices(frameBuffer, kColorChannels, image, dataWindow.min.x, dataWindow.min.y);

    bool legacyVariance = false;
    if (standardError) {
      const int present = channelsPresent(channels, kStandardErrorChannels);
      const int legacy = channelsPresent(channels, kLegacyVarianceChannels);
      legacyVariance = present == 0 && legacy == 3;
      if (present == 3 || legacyVariance) {
        *standardError = Image(width, height);
        addSlices(frameBuffer, legacyVariance ? kLegacyVarianceChannels : kStandardErrorChannels, *standardError,
                  dataWindow.min.x, dataWindow.min.y);
      } else if (present == 0 && legacy == 0) {
        *standardError = Image();
      } else {
        throw Error("EXR '" + path + "' has only some of the " +
                    (present ? "standardError.R/G/B" : "variance.R/G/B") + " channels");
      }
    }

    if (meta) {
      *meta = ExrMetadata();
      for (auto it = header.begin(); it != header.end(); ++it) {
        const std::string name = it.name();
        if (kStructuralAttributes.count(name)) continue;
        const Imf::Attribute& attribute = it.attribute();
        if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&attribute))
          meta->strings[name] = text->value();
        else if (const auto* integer = dynamic_cast<const Imf::IntAttribute*>(&attribute))
          meta->ints[name] = integer->value();
        else if (const auto* real = dynamic_cast<const Imf::FloatAttribute*>(&attribute))
          meta->floats[name] = real->value();
      }
    }

    file.setFrameBuffer(frameBuffer);
    file.readPixels(dataWindow.min.y, dataWindow.max.y);
    if (legacyVariance)
      for (float& v : standardError->rgb) v = v >= 0.0f ? std::sqrt(v) : v;  // a negative one stays invalid
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("cannot read EXR '" + path + "': " + oneLine(e.what()));
  }
}

Image readExrChannels(const std::string& path, const std::vector<std::string>& names) {
  const int64_t fileSize = regularFileSize(path);
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    checkDataWindow(path, window, 3, fileSize);
    Image image(window.max.x - window.min.x + 1, window.max.y - window.min.y + 1);
    for (const std::string& name : names)
      if (!file.header().channels().findChannel(name)) throw Error("EXR '" + path + "' has no " + name + " channel");
    Imf::FrameBuffer frameBuffer;
    addSlices(frameBuffer, names, image, window.min.x, window.min.y);
    file.setFrameBuffer(frameBuffer);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("cannot read EXR '" + path + "': " + oneLine(e.what()));
  }
}

}  // namespace mixtrace
