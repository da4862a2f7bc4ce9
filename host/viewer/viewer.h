#pragma once
// `mixtrace view`: a window that shows the scene converging, rendered progressively by the same
// wavefront renderer as `render` (one per method, made when first shown), with live method
// switching, a split view of two methods at equal time, debug views of the cells, an orbit/pan/
// zoom/fly camera, and a key that saves the film as `render` would. --script replays input
// (viewer/input.h) so the viewer can be tested headless under Xvfb.
#include <string>

#include "session/options.h"

namespace mixtrace {

// Returns the process exit code (non-zero when validation reported errors).
int runViewer(const RenderOptions& options, const std::string& scriptPath);

}  // namespace mixtrace
