#pragma once
// The scene `render` and `view` use when none is given: both commands share this one lookup.
#include <string>

namespace mixtrace {

// The shipped default scene (scenes/cornell_box.gltf), found next to the source tree or the binary.
std::string defaultScenePath();

}  // namespace mixtrace
