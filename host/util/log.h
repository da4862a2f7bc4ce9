#pragma once
#include <string>

namespace mixtrace {

// Warnings go to stderr, one line each, prefixed "mixtrace: warning: ".
void warn(const std::string& message);
// Informational lines (stderr), suppressed by setQuiet(true).
void info(const std::string& message);
void setQuiet(bool quiet);

}  // namespace mixtrace
