#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// Test kernel: every invocation finds or claims the cell of one (position, normal, material) given
// by the host (rayOrigin = position, rayDirection = normal, rngState = material) and writes the
// slot over the material in rngState[i].
#include "gpu/buffers.glsl"

layout(scalar, binding = BINDING_CELL_KEYS) buffer CellKeyBuf { uint64_t cellKeys[]; };
#define CELL_KEY_LOAD(slot) cellKeys[slot]
#define CELL_KEY_CAS(slot, expected, desired) atomicCompSwap(cellKeys[slot], expected, desired)
#include "shared/cms_cells.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.pathCount) return;
  CellGrid g;
  g.origin = pc.gridOrigin;
  g.invCellSize = pc.gridInvCellSize;
  g.tableSize = pc.cellTableSize;
  rngState[i] = findOrInsertCell(g, rayOrigin[i], rayDirection[i], rngState[i]);
}
