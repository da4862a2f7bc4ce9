#pragma once
#include <stdexcept>
#include <string>

namespace mixtrace {

// An error the user can act on. main() prints what() as one line ("mixtrace: error: ...") and
// exits non-zero; nothing below main() prints errors or calls exit().
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace mixtrace
