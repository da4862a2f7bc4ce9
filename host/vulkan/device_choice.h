#pragma once
// Which Vulkan device `--device` names, decided from the devices' names and whether each can run
// mixtrace. Pure (no Vulkan calls), so the rule is unit tested without two GPUs.
//
//   ""          the first usable discrete GPU, else the first usable device
//   "1", "-1"   an integer is an index, only (never a name: "1" must not match "LLVM 15.0.6")
//   "nvidia"    a case-insensitive substring of the name, which must match exactly one device
//
// Anything else (index out of range, no match, several matches, a match that cannot run mixtrace)
// throws mixtrace::Error with one line that lists the devices.
#include <cstddef>
#include <string>
#include <vector>

namespace mixtrace {

struct DeviceCandidate {
  std::string name;
  bool discrete = false;        // VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: preferred by default
  std::string unusableReason;   // empty when the device can run mixtrace
  bool usable() const { return unusableReason.empty(); }
};

size_t chooseDevice(const std::string& request, const std::vector<DeviceCandidate>& devices);

// "0: NAME, 1: NAME (cannot run mixtrace: REASON)": the list the errors quote.
std::string deviceListText(const std::vector<DeviceCandidate>& devices);

}  // namespace mixtrace
