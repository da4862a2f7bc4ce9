#pragma once
// The hashed cell grid of controlled mixture sampling (shared/cms_cells.h) for a scene: where it
// starts, how large its cells are and how many slots its table has. One definition for both
// backends, so the Vulkan renderer and the CPU reference key the same vertices to the same cells.
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace mixtrace {

// The fields of shared::CellGrid (that header needs its includer's buffer macros, so it is not
// included here).
struct CellGridSetup {
  glm::vec3 origin{0.0f};   // a little below the scene bounds' minimum
  float invCellSize = 1.0f; // cells per unit length
  uint32_t tableSize = 1;   // slots of the key table (a power of two)
};

// `cells` cells along the scene's longest axis; `clusters` (L) bounds the table so that its float
// statistics stay within 64 MiB.
CellGridSetup makeCellGrid(const Bounds& sceneBounds, uint32_t cells, uint32_t clusters);

// Slots of the cell table: room for about 8 cells per grid cell on a surface-like layer of the
// grid, a power of two.
uint32_t cellTableSizeFor(uint32_t cells, uint32_t clusters);

// The most slots the table may have with `clusters` clusters: its float statistics within 64 MiB.
uint64_t cellTableSlotLimit(uint32_t clusters);

}  // namespace mixtrace
