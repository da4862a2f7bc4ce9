#pragma once
// The files a glTF scene reads besides itself (external buffers and images), found by a quick
// look at its JSON, so that no output is allowed to overwrite them.
#include <string>
#include <vector>

namespace mixtrace {

// Best effort and silent: a file that cannot be read or parsed yields nothing (the loader then
// reports the problem properly). Only a regular file is read, and only up to a size limit; URIs
// are resolved against the scene's directory ("data:" URIs name no file).
std::vector<std::string> filesReferencedByScene(const std::string& scenePath);

}  // namespace mixtrace
