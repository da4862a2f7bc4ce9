#include "util/log.h"

#include <cstdio>

namespace mixtrace {
namespace {
bool gQuiet = false;
}

void warn(const std::string& message) { std::fprintf(stderr, "mixtrace: warning: %s\n", message.c_str()); }

void info(const std::string& message) {
  if (!gQuiet) std::fprintf(stderr, "mixtrace: %s\n", message.c_str());
}

void setQuiet(bool quiet) { gQuiet = quiet; }

}  // namespace mixtrace
