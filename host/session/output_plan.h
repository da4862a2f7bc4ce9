#pragma once
// The files `render` (and the viewer's save key) will write, decided and checked before the scene
// is loaded: the image's format from its extension, every directory writable, no two outputs the
// same file and none of them the scene or a file it reads.
#include <string>
#include <vector>

#include "session/options.h"

namespace mixtrace {

struct OutputPlan {
  std::string image;     // --out, or "<scene stem>.exr" in the current directory
  std::string preview;   // the PNG beside an EXR; "" when none
  std::string stats;     // --stats; "" when none
  std::vector<std::string> aovs;   // --aov's layers, in its order: albedo, normal, depth
};

// The layers --aov names (albedo, normal, depth; comma-separated, each once). Throws
// mixtrace::Error naming what is wrong.
std::vector<std::string> parseAovList(const std::string& list);

// Throws mixtrace::Error (one line naming the option) when the plan is not safe to carry out.
OutputPlan planRenderOutputs(const RenderOptions& o, const std::string& scenePath);

// The viewer: --out, where P saves, when given (without it P picks a fresh name).
void checkViewerOutputs(const RenderOptions& o, const std::string& scenePath);

}  // namespace mixtrace
