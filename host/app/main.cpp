// mixtrace: command-line entry point. Every failure the user can cause ends here as one line
// on stderr and a non-zero exit code.
#include <cstdio>
#include <exception>
#include <new>

#include "app/options.h"
#include "app/render_command.h"
#include "util/error.h"

int main(int argc, char** argv) {
  using namespace mixtrace;
  try {
    ParsedCommandLine cl = parseCommandLine(argc, argv);
    switch (cl.command) {
      case Command::Help: std::fputs(helpText().c_str(), stdout); return 0;
      case Command::Version: std::printf("mixtrace %s\n", MIXTRACE_VERSION); return 0;
      case Command::Render: return runRender(cl.render);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "mixtrace: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mixtrace: error: out of host memory (try a smaller image or scene)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mixtrace: error: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
