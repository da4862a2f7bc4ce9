#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// Test kernel: the cell table's concurrent find-or-insert (tests/cell_lookup_interface.h).
#include "tests/cell_lookup_interface.h"
#define PASS_BUFFERS CELL_LOOKUP_BUFFERS
#define PASS_CONSTANTS CellLookupConstants
#include "gpu/buffers.glsl"

#define CELL_KEY_LOAD(slot) cellKeys[slot]
#define CELL_KEY_CAS(slot, expected, desired) atomicCompSwap(cellKeys[slot], expected, desired)
#include "shared/cms_cells.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.pointCount) return;
  CellGrid g;
  g.origin = pc.gridOrigin;
  g.invCellSize = pc.gridInvCellSize;
  g.tableSize = pc.cellTableSize;
  rngState[i] = findOrInsertCell(g, rayOrigin[i], rayDirection[i], rngState[i]);
}
