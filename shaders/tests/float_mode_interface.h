// Test kernel tests/float_mode.comp: scales the host's values (throughput[i] *= pc.scale), so
// tests/gpu/denormal_mode_test.cpp can see whether the device's threads flush denormal operands
// and results to zero (host/vulkan/denormal_mode.h).
#ifndef MIXTRACE_TESTS_FLOAT_MODE_INTERFACE_H
#define MIXTRACE_TESTS_FLOAT_MODE_INTERFACE_H
#include "shared/path_state.h"

#define FLOAT_MODE_BUFFERS(X) BUFFER_THROUGHPUT(X)

SHARED_BEGIN
struct FloatModeConstants {
  uint count;   // values in throughput
  float scale;  // each is multiplied by it
};
SHARED_END
#endif
