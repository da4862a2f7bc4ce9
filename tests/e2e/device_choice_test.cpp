// --device (vulkan/device_choice.h): an integer is an index only, a name is a case-insensitive
// substring that must match exactly one device; every refusal is one line listing the devices.
// And `mixtrace --list-devices` on the machine's driver (lavapipe here).
#include "vulkan/device_choice.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/run_binary.h"
#include "util/error.h"

namespace mixtrace {
namespace {

const std::string kLavapipe = "llvmpipe (LLVM 15.0.6, 256 bits)";

std::vector<DeviceCandidate> lavapipeOnly() { return {{kLavapipe, false, ""}}; }

std::vector<DeviceCandidate> twoGpus() {
  return {{kLavapipe, false, ""},
          {"NVIDIA GeForce RTX 4090", true, ""},
          {"NVIDIA GeForce GT 710", true, "needs Vulkan 1.2, has 1.1.0"}};
}

std::string errorOf(const std::string& request, const std::vector<DeviceCandidate>& devices) {
  try {
    chooseDevice(request, devices);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "--device " << request << " was accepted";
  return "";
}

void expectMentions(const std::string& message, const std::string& needle) {
  EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message;
}

TEST(DeviceChoice, AnIntegerIsAnIndexNeverADigitOfAName) {
  // The bug: "1" matched the '1' in "15.0.6" and rendered on device 0.
  const std::string message = errorOf("1", lavapipeOnly());
  expectMentions(message, "--device 1");
  expectMentions(message, "0: " + kLavapipe);   // the devices are listed
  EXPECT_EQ(chooseDevice("0", lavapipeOnly()), 0u);
  EXPECT_EQ(chooseDevice("1", twoGpus()), 1u);
  expectMentions(errorOf("-1", lavapipeOnly()), "no device with that index");
  expectMentions(errorOf("15", lavapipeOnly()), "no device with that index");
  expectMentions(errorOf("99999999999999999999", lavapipeOnly()), "no device with that index");
}

TEST(DeviceChoice, ANameMatchesByCaseInsensitiveSubstring) {
  EXPECT_EQ(chooseDevice("llvm", lavapipeOnly()), 0u);
  EXPECT_EQ(chooseDevice("LLVMpipe", lavapipeOnly()), 0u);
  EXPECT_EQ(chooseDevice("rtx 4090", twoGpus()), 1u);
  expectMentions(errorOf("radeon", twoGpus()), "no device name contains it");
}

TEST(DeviceChoice, AnAmbiguousNameIsRefusedWithTheMatches) {
  const std::string message = errorOf("nvidia", twoGpus());
  expectMentions(message, "matches 2 devices");
  expectMentions(message, "1: NVIDIA GeForce RTX 4090");
  expectMentions(message, "2: NVIDIA GeForce GT 710");
  EXPECT_EQ(message.find("0: llvmpipe"), std::string::npos) << message;
}

TEST(DeviceChoice, AnUnusableDeviceIsRefusedWithItsReason) {
  expectMentions(errorOf("2", twoGpus()), "needs Vulkan 1.2");
  expectMentions(errorOf("GT 710", twoGpus()), "needs Vulkan 1.2");
}

TEST(DeviceChoice, TheDefaultIsTheFirstUsableDiscreteGpu) {
  EXPECT_EQ(chooseDevice("", lavapipeOnly()), 0u);
  EXPECT_EQ(chooseDevice("", twoGpus()), 1u);
  std::vector<DeviceCandidate> none = {{"old GPU", true, "no 64-bit integer atomics"}};
  expectMentions(errorOf("", none), "no 64-bit integer atomics");
}

TEST(DeviceChoice, ListDevicesPrintsIndexNameTypeDriverAndUsability) {
  const testing::RunResult r = testing::runMixtrace("--list-devices");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const std::string& out = r.stdoutText;
  expectMentions(out, "0: llvmpipe");      // index and name
  expectMentions(out, "CPU");              // type
  expectMentions(out, "driver llvmpipe");  // VkPhysicalDeviceDriverProperties::driverName
  expectMentions(out, "Mesa");             // ... and driverInfo
  expectMentions(out, "usable");
  const testing::RunResult extra = testing::runMixtrace("--list-devices now");
  EXPECT_EQ(extra.exitCode, 1);
  expectMentions(extra.stderrText, "unexpected argument 'now'");
}

TEST(DeviceChoice, RenderRefusesAnIndexOutOfRange) {
  const testing::RunResult r = testing::runMixtrace("render -q --device 1 --spp 1 --width 4 --height 4 --out " + (std::filesystem::temp_directory_path() / "mixtrace_device_choice.exr").string());
  EXPECT_EQ(r.exitCode, 1);
  ASSERT_EQ(r.stderrLines().size(), 1u) << r.stderrText;
  expectMentions(r.stderrText, "mixtrace: error: --device 1: no device with that index");
}

// The device is chosen before the scene is loaded: a wrong --device costs no loading (no
// scene or method line comes before the error).
TEST(DeviceChoice, AWrongDeviceIsRefusedBeforeTheSceneIsLoaded) {
  const testing::RunResult r = testing::runMixtrace(
      "render --device 1 --spp 1 --width 4 --height 4 --out " +
      (std::filesystem::temp_directory_path() / "mixtrace_device_first.exr").string());
  EXPECT_EQ(r.exitCode, 1);
  ASSERT_EQ(r.stderrLines().size(), 1u) << r.stderrText;
  expectMentions(r.stderrText, "mixtrace: error: --device 1");
}

}  // namespace
}  // namespace mixtrace
