// Test kernel tests/cell_lookup.comp: every invocation finds or claims the cell of one (position,
// normal, material) given by the host (rayOrigin = position, rayDirection = normal, rngState =
// material) and writes the slot over the material in rngState[i] (tests/gpu/cms_cells_test.cpp).
#ifndef MIXTRACE_TESTS_CELL_LOOKUP_INTERFACE_H
#define MIXTRACE_TESTS_CELL_LOOKUP_INTERFACE_H
#include "shared/cms_state.h"
#include "shared/path_state.h"

#define CELL_LOOKUP_BUFFERS(X) BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_RNG(X) BUFFER_CELL_KEYS(X)

SHARED_BEGIN
struct CellLookupConstants {
  uint pointCount;
  vec3 gridOrigin;  // the CellGrid of shared/cms_cells.h
  float gridInvCellSize;
  uint cellTableSize;
};
SHARED_END
#endif
