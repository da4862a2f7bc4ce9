#include "vulkan/device_choice.h"

#include <cctype>

#include "util/error.h"

namespace mixtrace {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Optional sign, then digits only: the request is an index. Signed so that "-1" is reported as
// an index out of range rather than searched for in the names.
bool isInteger(const std::string& s) {
  size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
  if (i == s.size()) return false;
  for (; i < s.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
  return true;
}

std::string entry(const std::vector<DeviceCandidate>& devices, size_t i) {
  std::string text = std::to_string(i) + ": " + devices[i].name;
  if (!devices[i].usable()) text += " (cannot run mixtrace: " + devices[i].unusableReason + ")";
  return text;
}

size_t checkedUsable(const std::string& request, const std::vector<DeviceCandidate>& devices, size_t i) {
  if (!devices[i].usable())
    throw Error("--device " + request + ": device " + std::to_string(i) + " '" + devices[i].name +
                "' cannot run mixtrace: " + devices[i].unusableReason);
  return i;
}

}  // namespace

std::string deviceListText(const std::vector<DeviceCandidate>& devices) {
  std::string text;
  for (size_t i = 0; i < devices.size(); ++i) text += (i ? ", " : "") + entry(devices, i);
  return text;
}

size_t chooseDevice(const std::string& request, const std::vector<DeviceCandidate>& devices) {
  const std::string listed = " (devices: " + deviceListText(devices) + "; see mixtrace --list-devices)";
  if (request.empty()) {
    size_t chosen = devices.size();
    for (size_t i = 0; i < devices.size(); ++i) {
      if (!devices[i].usable()) continue;
      if (chosen == devices.size()) chosen = i;
      if (devices[i].discrete && !devices[chosen].discrete) chosen = i;
    }
    if (chosen == devices.size())
      throw Error("no Vulkan device can run mixtrace" + listed);
    return chosen;
  }
  if (isInteger(request)) {
    // More digits than any device count could need is out of range too (and would overflow).
    const bool inRange = request[0] != '-' && request.size() <= 6 && std::stoul(request) < devices.size();
    if (!inRange) throw Error("--device " + request + ": no device with that index" + listed);
    return checkedUsable(request, devices, std::stoul(request));
  }
  std::vector<size_t> matches;
  for (size_t i = 0; i < devices.size(); ++i)
    if (lower(devices[i].name).find(lower(request)) != std::string::npos) matches.push_back(i);
  if (matches.empty()) throw Error("--device " + request + ": no device name contains it" + listed);
  if (matches.size() > 1) {
    std::string names;
    for (size_t i : matches) names += (names.empty() ? "" : ", ") + entry(devices, i);
    throw Error("--device " + request + " matches " + std::to_string(matches.size()) + " devices (" + names +
                "); give the index or more of the name");
  }
  return checkedUsable(request, devices, matches[0]);
}

}  // namespace mixtrace
