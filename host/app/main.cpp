// mixtrace: command-line entry point. Every failure the user can cause ends here as one line
// on stderr and a non-zero exit code: 1 for render (and help/version), 2 for compare, whose exit
// code 1 already means "the images differ" (diff(1)'s convention).
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include "app/compare_command.h"
#include "session/options.h"
#include "app/render_command.h"
#include "util/error.h"
#include "viewer/viewer.h"
#include "vulkan/context.h"

int main(int argc, char** argv) {
  using namespace mixtrace;
  // Decided from argv rather than the parse result, so that parse errors get it too.
  const bool comparing = argc > 1 && argv[1] && std::strcmp(argv[1], "compare") == 0;
  const int userErrorExit = comparing ? kCompareExitError : 1;
  try {
    ParsedCommandLine cl = parseCommandLine(argc, argv);
    switch (cl.command) {
      case Command::Help: std::fputs(helpText().c_str(), stdout); return 0;
      case Command::Version: std::printf("mixtrace %s\n", MIXTRACE_VERSION); return 0;
      case Command::ListDevices: std::fputs(describeVulkanDevices().c_str(), stdout); return 0;
      case Command::Render: return runRender(cl.render);
      case Command::Compare: return runCompare(cl.compare);
      case Command::View: return runViewer(cl.render, cl.viewScript);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "mixtrace: error: %s\n", e.what());
    return userErrorExit;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mixtrace: error: out of host memory (try a smaller image or scene)\n");
    return userErrorExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mixtrace: error: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
