// Issue 11.4: `--variance` must stay finite and meaningful over the whole float range of the
// image itself. The film kept Welford's M2 in float, which scales with the square of the image:
// emitters of 1e20 gave NaN variances and emitters of 1e-30 exactly 0, so `compare` called two
// correct renders different. The film now keeps sqrt(M2) and the EXR the standard error of the
// mean (shared/film.h, output/exr_io.h).
#include <cmath>
#include <ostream>
#include <string>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include "output/exr_io.h"
#include "support/hard_scenes.h"
#include "support/render_agreement.h"

using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

struct RadianceCase {
  const char* backend;
  // Of the room's one light (the unscaled room's is 5). The camera does not see the light, so
  // the pixels are ~10x dimmer: at 1e20 a float M2 only just fits; 1e22 overflows it.
  float radiance;
  const char* name;
};

void PrintTo(const RadianceCase& c, std::ostream* os) { *os << c.backend << " radiance " << c.radiance; }

class VarianceRange : public ::testing::TestWithParam<RadianceCase> {};

TEST_P(VarianceRange, StandardErrorsAreFiniteAndCompareAgreesOnTwoSeeds) {
  const RadianceCase c = GetParam();
  const std::string gltf = hard::scaledRoomScene(1.0, c.radiance / 5.0f);
  const std::string a = std::string("room_") + c.name + "_a", b = std::string("room_") + c.name + "_b";
  RenderWithStats first, second;
  ASSERT_NO_FATAL_FAILURE(renderScene("variance_range", a, gltf, c.backend, 1, first));
  ASSERT_NO_FATAL_FAILURE(renderScene("variance_range", b, gltf, c.backend, 2, second));

  size_t positive = 0, invalid = 0;
  for (float se : first.variance.rgb) {   // readExr returns standard errors
    invalid += !(std::isfinite(se) && se >= 0.0f);
    positive += se > 0.0f;
  }
  EXPECT_EQ(invalid, 0u) << "non-finite or negative standard errors";
  EXPECT_GT(positive, first.variance.rgb.size() / 2) << "a noisy render has a non-zero standard error in most pixels";

  const ComparisonResult cmp = compareRenders(first, second);
  EXPECT_TRUE(cmp.agree) << c.backend << ", radiance " << c.radiance << ": " << cmp.summary();
  // And the command line says so.
  const RunResult cli = runMixtrace("compare " + agreementImagePath("variance_range", a, c.backend).string() + " " +
                                    agreementImagePath("variance_range", b, c.backend).string());
  EXPECT_EQ(cli.exitCode, 0) << cli.stdoutText << cli.stderrText;
}

INSTANTIATE_TEST_SUITE_P(Radiances, VarianceRange,
                         ::testing::Values(RadianceCase{"vulkan", 1e20f, "1e20"}, RadianceCase{"vulkan", 1e22f, "1e22"},
                                           RadianceCase{"vulkan", 1e-30f, "1em30"}, RadianceCase{"cpu", 1e20f, "1e20"},
                                           RadianceCase{"cpu", 1e22f, "1e22"}, RadianceCase{"cpu", 1e-30f, "1em30"}),
                         [](const auto& info) { return std::string(info.param.backend) + "_" + info.param.name; });

// Files written before the change hold the variance of the mean (variance.R/G/B): readExr
// still reads them, as standard errors.
TEST(VarianceRangeLegacyFiles, VarianceChannelsAreReadAsStandardErrors) {
  const std::string path = (scratchDir("variance_range") / "legacy.exr").string();
  float rgb[3] = {1.0f, 2.0f, 3.0f}, variance[3] = {4.0f, 0.25f, 1e-20f};
  {
    Imf::Header header(1, 1);
    Imf::FrameBuffer frame;
    const char* names[6] = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
    for (int c = 0; c < 6; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      float* value = c < 3 ? &rgb[c] : &variance[c - 3];
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(value), sizeof(float), sizeof(float)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(1);
  }
  Image standardError;
  const Image image = readExr(path, nullptr, &standardError);
  ASSERT_EQ(standardError.width, 1);
  EXPECT_EQ(image.rgb[1], 2.0f);
  EXPECT_FLOAT_EQ(standardError.rgb[0], 2.0f);
  EXPECT_FLOAT_EQ(standardError.rgb[1], 0.5f);
  EXPECT_FLOAT_EQ(standardError.rgb[2], 1e-10f);
}

}  // namespace
