#pragma once
// Statistical render tests run small by default (CI's 2 cores); `ctest -L long` runs the same
// executables again with MIXTRACE_TEST_LONG=1, where they use more samples and larger images.
#include <cstdlib>

namespace mixtrace::testing {

inline bool longTests() {
  const char* v = std::getenv("MIXTRACE_TEST_LONG");
  return v && *v && *v != '0';
}

// `quick` by default, `thorough` under `ctest -L long`.
template <class T> T byTestLevel(T quick, T thorough) { return longTests() ? thorough : quick; }

}  // namespace mixtrace::testing
