// OpenEXR round trips: exact float bits (tiny, huge, non-finite), metadata, variance channels,
// and the errors a user can cause.
#include "output/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <half.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "support/scratch_files.h"
#include "util/error.h"

namespace mixtrace {
namespace {

class ExrIo : public mixtrace::testing::ScratchFiles {};

uint32_t bitsOf(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// Every float must come back bit for bit: the EXR is the renderer's result, not a preview.
void expectSameBits(const Image& expected, const Image& actual) {
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
  for (size_t i = 0; i < expected.rgb.size(); ++i)
    EXPECT_EQ(bitsOf(actual.rgb[i]), bitsOf(expected.rgb[i])) << "float " << i << ": " << expected.rgb[i]
                                                               << " came back as " << actual.rgb[i];
}

Image makeTestImage(int width, int height) {
  const float special[] = {0.0f,
                           -0.0f,
                           1.0f,
                           1.0f / 3.0f,
                           -2.5f,
                           std::numeric_limits<float>::denorm_min(),
                           1e-40f,
                           std::numeric_limits<float>::min(),
                           1e-30f,
                           3.0e38f,
                           std::numeric_limits<float>::max(),
                           65504.0f,
                           65505.0f,  // just past the half-float range: catches HALF storage
                           std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::quiet_NaN()};
  Image image(width, height);
  const size_t count = sizeof(special) / sizeof(special[0]);
  for (size_t i = 0; i < image.rgb.size(); ++i)
    image.rgb[i] = i < count ? special[i] : 0.001f * static_cast<float>(i) + 0.5f;
  return image;
}

TEST_F(ExrIo, RoundTripKeepsExactValuesAndMetadata) {
  const Image image = makeTestImage(7, 5);  // odd sizes catch stride mistakes
  ExrMetadata meta;
  meta.ints["spp"] = 256;
  meta.ints["negative"] = -17;
  meta.floats["renderSeconds"] = 12.375f;
  meta.floats["tiny"] = 1e-38f;
  meta.strings["method"] = "pt-power";
  meta.strings["scene"] = "scenes/cornell box.gltf";
  meta.strings["empty"] = "";

  const std::string path = tempPath("a.exr");
  writeExr(path, image, meta);

  ExrMetadata readMeta;
  Image variance(3, 3);  // must be reset: the file has no variance channels
  const Image back = readExr(path, &readMeta, &variance);
  expectSameBits(image, back);
  EXPECT_EQ(readMeta.ints, meta.ints);
  EXPECT_EQ(readMeta.floats, meta.floats);
  EXPECT_EQ(readMeta.strings, meta.strings);
  EXPECT_EQ(variance.width, 0);
  EXPECT_TRUE(variance.rgb.empty());

  // Reading without the optional outputs works too.
  expectSameBits(image, readExr(path));
}

TEST_F(ExrIo, VarianceChannelsRoundTrip) {
  const Image image = makeTestImage(4, 3);
  Image variance(4, 3);
  for (size_t i = 0; i < variance.rgb.size(); ++i) variance.rgb[i] = 1e-6f * static_cast<float>(i * i) + 1e-20f;
  const std::string path = tempPath("v.exr");
  writeExr(path, image, ExrMetadata(), &variance);

  Image varianceBack;
  const Image back = readExr(path, nullptr, &varianceBack);
  expectSameBits(image, back);
  expectSameBits(variance, varianceBack);
}

TEST_F(ExrIo, ReadsAnOffsetDataWindowAndHalfChannels) {
  // A file not written by mixtrace: data window starting at (2, 3), HALF channels.
  const int width = 3, height = 2;
  Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(9, 9)),
                     Imath::Box2i(Imath::V2i(2, 3), Imath::V2i(2 + width - 1, 3 + height - 1)));
  float values[3][height][width];
  half halves[3][height][width];  // OpenEXR converts on input only, so the file is written from halves
  Imf::FrameBuffer frameBuffer;
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::HALF));
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        values[c][y][x] = static_cast<float>(c * 100 + y * 10 + x);  // exact in half
        halves[c][y][x] = half(values[c][y][x]);
      }
    char* base = reinterpret_cast<char*>(&halves[c][0][0]) - (2 + 3 * width) * sizeof(half);
    frameBuffer.insert(names[c], Imf::Slice(Imf::HALF, base, sizeof(half), width * sizeof(half)));
  }
  const std::string path = tempPath("offset.exr");
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(height);
  }
  const Image image = readExr(path);
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(image.pixel(x, y)[c], values[c][y][x]) << x << "," << y << "," << c;
}

void expectOneLineError(const std::function<void()>& action, const std::string& needle) {
  try {
    action();
    ADD_FAILURE() << "no Error thrown";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_F(ExrIo, ErrorOnNonExrAndMissingFiles) {
  const std::string path = tempPath("not.exr");
  std::ofstream(path) << "this is a text file, not an image\n";
  expectOneLineError([&] { readExr(path); }, path);
  const std::string missing = tempPath("missing.exr");
  expectOneLineError([&] { readExr(missing); }, missing);
}

TEST_F(ExrIo, ErrorOnMissingColorChannels) {
  Imf::Header header(2, 2);
  header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
  float luminance[4] = {1, 2, 3, 4};
  Imf::FrameBuffer frameBuffer;
  frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(luminance), sizeof(float), 2 * sizeof(float)));
  const std::string path = tempPath("y.exr");
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(2);
  }
  expectOneLineError([&] { readExr(path); }, "R channel");
}

TEST_F(ExrIo, ErrorOnUnwritablePath) {
  const Image image = makeTestImage(2, 2);
  const std::string path = tempPath("no_such_dir") + "/sub/out.exr";
  expectOneLineError([&] { writeExr(path, image, ExrMetadata()); }, path);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(ExrIo, ErrorOnReservedAttributeOrMismatchedVariance) {
  const Image image = makeTestImage(2, 2);
  ExrMetadata meta;
  meta.strings["compression"] = "none";
  expectOneLineError([&] { writeExr(tempPath("r.exr"), image, meta); }, "compression");

  const Image wrongSize(3, 2);
  expectOneLineError([&] { writeExr(tempPath("m.exr"), image, ExrMetadata(), &wrongSize); }, "variance");
}

}  // namespace
}  // namespace mixtrace
