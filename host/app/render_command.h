#pragma once
#include "session/options.h"

namespace mixtrace {

// `mixtrace render`: load, prepare, render on the chosen backend, write EXR (+ PNG, + stats).
// Returns the process exit code; throws mixtrace::Error for user-facing failures.
int runRender(const RenderOptions& options);

}  // namespace mixtrace
