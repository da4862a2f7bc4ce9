#include "cms/cell_grid.h"

#include <algorithm>

#include "shared/cms_layouts.h"

namespace mixtrace {
namespace {

uint32_t floorPowerOfTwo(uint64_t n) {
  uint32_t p = 1;
  while (uint64_t(p) * 2 <= n && p < (1u << 30)) p *= 2;
  return p;
}

}  // namespace

uint64_t cellTableSlotLimit(uint32_t clusters) {
  return (64ull << 20) / (sizeof(float) * shared::cellStatsStride(clusters));
}

uint32_t cellTableSizeFor(uint32_t cells, uint32_t clusters) {
  uint64_t wanted = std::max<uint64_t>(4096, uint64_t(48) * cells * cells);
  return floorPowerOfTwo(std::min(wanted * 2 - 1, cellTableSlotLimit(clusters)));
}

CellGridSetup makeCellGrid(const Bounds& b, uint32_t cells, uint32_t clusters) {
  CellGridSetup grid;
  float longest = std::max({b.extent().x, b.extent().y, b.extent().z, 1e-6f});
  // A margin around the bounds: points on them (or just outside, through rounding) stay inside.
  grid.origin = b.min - 1e-3f * longest;
  grid.invCellSize = float(cells) / (longest * 1.002f);
  grid.tableSize = cellTableSizeFor(cells, clusters);
  return grid;
}

}  // namespace mixtrace
