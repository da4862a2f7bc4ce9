#pragma once
#include "app/options.h"

namespace mixtrace {

// `mixtrace render`: load, prepare, render on the chosen backend, write EXR (+ PNG, + stats).
// Returns the process exit code; throws mixtrace::Error for user-facing failures.
int runRender(const RenderOptions& options);

// The shipped default scene (scenes/cornell_box.gltf), found next to the source tree or the binary.
std::string defaultScenePath();

}  // namespace mixtrace
