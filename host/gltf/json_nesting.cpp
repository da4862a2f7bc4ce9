#include "gltf/json_nesting.h"

namespace mixtrace {

size_t jsonNestingExceededAt(const char* json, size_t size, int maxDepth) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = json[i];
    if (inString) {
      if (c == '\\') {
        ++i;  // whatever is escaped, it neither ends the string nor nests
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > maxDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return kJsonNestingOk;
}

}  // namespace mixtrace
