// The spatial cells that share one control variate (docs/estimator.md §5, §7): a hashed sparse grid
// keyed by position (cells along the longest scene axis set by --cells), by the dominant axis of
// the geometric normal (6 classes), so a floor and the wall beside it never share coefficients, and
// by the material, so a mirror and a rough surface next to it (whose integrands differ most) never
// do either.
// Open addressing with linear probing; a slot is claimed with a 64-bit compare-and-swap. When no
// free slot is found within kCellProbes, the vertex gets no cell: it then simply uses no control
// variate and contributes no statistics, which keeps the estimator unbiased.
//
// The includer defines CELL_KEY_CAS(slot, expected, desired) -> the previous key (an atomic
// compare-and-swap on the uint64 key table) and CELL_KEY_LOAD(slot).
#ifndef MIXTRACE_SHARED_CMS_CELLS_H
#define MIXTRACE_SHARED_CMS_CELLS_H
#include "shared/cms_layouts.h"
#include "shared/dialect.h"
#include "shared/hash64.h"
SHARED_BEGIN_WITH_BUFFERS

const uint kCellProbes = 16u;
const uint kCellCoordBits = 16u;     // up to 2^16 cells per axis (--cells allows 4096)
const uint kCellMaterialBits = 13u;  // materials beyond 8192 share keys modulo 8192 (still unbiased)

struct CellGrid {
  vec3 origin;        // scene bounds minimum
  float invCellSize;  // cells per unit length
  uint tableSize;     // slots in the key table (a power of two)
  uint pad0;
  uint pad1;
  uint pad2;
};

// 0 = dominant axis +x, 1 = -x, 2 = +y, 3 = -y, 4 = +z, 5 = -z.
SHARED_FN uint normalClass(vec3 n) {
  vec3 a = abs(n);
  if (a.x >= a.y && a.x >= a.z) return n.x >= 0.0f ? 0u : 1u;
  if (a.y >= a.z) return n.y >= 0.0f ? 2u : 3u;
  return n.z >= 0.0f ? 4u : 5u;
}

SHARED_FN uint cellCoordinate(float x) {
  // Clamped so points on (or, through rounding, just outside) the bounds still find a cell.
  return uint(clamp(floor(x), 0.0f, float((1u << kCellCoordBits) - 1u)));
}

// Bits 0-47: cell coordinates; 48-50: normal class + 1 (so never 0: 0 marks an empty slot);
// 51-63: material.
SHARED_FN uint64_t cellKey(CellGrid g, vec3 p, vec3 n, uint material) {
  vec3 c = (p - g.origin) * g.invCellSize;
  uint64_t key = uint64_t(cellCoordinate(c.x));
  key |= uint64_t(cellCoordinate(c.y)) << 16;
  key |= uint64_t(cellCoordinate(c.z)) << 32;
  key |= uint64_t(normalClass(n) + 1u) << 48;
  key |= uint64_t(material & ((1u << kCellMaterialBits) - 1u)) << 51;
  return key;
}

// The cell table's hash of a key (shared/hash64.h).
SHARED_FN uint hashCellKey(uint64_t key) { return hash64To32(key); }

// The slot of the cell holding (p, n, material): found, or claimed; kNoCell when the probe
// sequence is full.
SHARED_FN uint findOrInsertCell(CellGrid g, vec3 p, vec3 n, uint material) {
  uint64_t key = cellKey(g, p, n, material);
  uint mask = g.tableSize - 1u;
  uint slot = hashCellKey(key) & mask;
  for (uint i = 0u; i < kCellProbes; ++i) {
    uint64_t seen = CELL_KEY_LOAD(slot);
    if (seen == key) return slot;
    if (seen == uint64_t(0)) {
      uint64_t previous = CELL_KEY_CAS(slot, uint64_t(0), key);
      if (previous == uint64_t(0) || previous == key) return slot;
    }
    slot = (slot + 1u) & mask;
  }
  return kNoCell;
}

SHARED_END_WITH_BUFFERS
#endif
