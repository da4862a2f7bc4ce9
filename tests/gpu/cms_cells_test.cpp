// The CMS cell grid (shaders/shared/cms_cells.h): the same cell for points of one grid cell and
// normal class, different cells otherwise, graceful failure when the table is full, and the same
// behaviour from the GPU's concurrent compare-and-swap insertion as from the C++ build.
#include <atomic>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "shared/bindings.h"
#include "tests/cell_lookup_interface.h"
#include "shared/layouts.h"
#include "vulkan/buffer.h"
#include "vulkan/context.h"
#include "vulkan/compute_pass.h"

namespace {
std::vector<std::atomic<uint64_t>>* gKeys = nullptr;
uint64_t casKey(uint32_t slot, uint64_t expected, uint64_t desired) {
  (*gKeys)[slot].compare_exchange_strong(expected, desired);
  return expected;  // the previous value, as GLSL's atomicCompSwap returns it
}
}  // namespace

#define CELL_KEY_LOAD(slot) ((*gKeys)[slot].load())
#define CELL_KEY_CAS(slot, expected, desired) casKey(slot, expected, desired)
#include "shared/cms_cells.h"

using namespace mixtrace;
using shared::CellGrid;

namespace {

CellGrid grid(float cellsPerUnit, uint32_t tableSize) {
  CellGrid g{};
  g.origin = glm::vec3(0.0f);
  g.invCellSize = cellsPerUnit;
  g.tableSize = tableSize;
  return g;
}

struct Table {
  explicit Table(size_t n) : keys(n) {
    for (auto& k : keys) k = 0;
    gKeys = &keys;
  }
  std::vector<std::atomic<uint64_t>> keys;
};

}  // namespace

TEST(CmsCells, SameCellSameSlotOtherCellsOtherSlots) {
  Table t(1024);
  CellGrid g = grid(4.0f, 1024);  // cells of 0.25
  glm::vec3 up(0, 1, 0);
  uint32_t a = shared::findOrInsertCell(g, glm::vec3(0.30f, 0.30f, 0.30f), up, 0);
  uint32_t b = shared::findOrInsertCell(g, glm::vec3(0.45f, 0.26f, 0.49f), up, 0);
  uint32_t c = shared::findOrInsertCell(g, glm::vec3(0.55f, 0.30f, 0.30f), up, 0);
  uint32_t wall = shared::findOrInsertCell(g, glm::vec3(0.30f, 0.30f, 0.30f), glm::vec3(1, 0.2f, 0), 0);
  uint32_t mirror = shared::findOrInsertCell(g, glm::vec3(0.30f, 0.30f, 0.30f), up, 1);
  uint32_t far = shared::findOrInsertCell(g, glm::vec3(0.30f, 0.30f, 0.30f), up, 1 + (1 << 13));
  EXPECT_NE(a, shared::kNoCell);
  EXPECT_EQ(a, b) << "points of one cell and normal class share a cell";
  EXPECT_NE(a, c) << "the neighbouring cell";
  EXPECT_NE(a, wall) << "a wall and a floor at the same place";
  EXPECT_NE(a, mirror) << "two materials at the same place";
  EXPECT_EQ(mirror, far) << "material indices wrap at 2^13 (sharing a cell stays unbiased)";
  EXPECT_EQ(shared::normalClass(glm::vec3(0, -1, 0)), 3u);
  EXPECT_EQ(shared::normalClass(glm::vec3(0.1f, 0.2f, -0.9f)), 5u);
}

TEST(CmsCells, PointsOutsideTheBoundsAreClamped) {
  Table t(64);
  CellGrid g = grid(1.0f, 64);
  uint32_t s = shared::findOrInsertCell(g, glm::vec3(-1e-6f, -5.0f, 1e30f), glm::vec3(0, 0, 1), 0);
  EXPECT_NE(s, shared::kNoCell);
  EXPECT_NE(shared::cellKey(g, glm::vec3(0.0f), glm::vec3(0, 0, 1), 0), uint64_t(0));
}

TEST(CmsCells, FullTableDegradesToNoCell) {
  Table t(16);
  CellGrid g = grid(1.0f, 16);
  std::set<uint32_t> slots;
  int none = 0;
  for (int i = 0; i < 100; ++i) {
    uint32_t s = shared::findOrInsertCell(g, glm::vec3(float(i) + 0.5f, 0.5f, 0.5f), glm::vec3(0, 1, 0), 0);
    if (s == shared::kNoCell) ++none;
    else slots.insert(s);
  }
  EXPECT_EQ(slots.size(), 16u) << "every slot is used before any vertex is refused";
  EXPECT_EQ(none, 100 - 16);
}

TEST(CmsCells, GpuInsertionIsConsistentUnderContention) {
  VulkanContext ctx(ContextOptions{"", true});
  ComputePass pass(ctx, "cell_lookup", BINDINGS_OF(CELL_LOOKUP_BUFFERS), sizeof(shared::CellLookupConstants), {});
  // 32768 points in 500 distinct cells (many threads race for the same cell), table of 1024.
  const uint32_t n = 32768, tableSize = 1024;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> cell(0, 499);
  std::uniform_real_distribution<float> jitter(0.05f, 0.95f);
  // Each of the 500 cells is a (position, material) pair: 250 places, 2 materials.
  std::vector<glm::vec3> positions(n), normals(n, glm::vec3(0, 1, 0));
  std::vector<uint32_t> materials(n);
  std::vector<int> cellOf(n);
  for (uint32_t i = 0; i < n; ++i) {
    cellOf[i] = cell(rng);
    materials[i] = uint32_t(cellOf[i] % 2) * 7u;
    int place = cellOf[i] / 2;
    positions[i] = glm::vec3(float(place % 50) + jitter(rng), float(place / 50) + jitter(rng), jitter(rng));
  }
  Buffer p = makeBuffer(ctx, positions, "positions"), nb = makeBuffer(ctx, normals, "normals");
  Buffer slots = makeBuffer(ctx, materials, "materials, then slots");
  Buffer keys = makeBuffer(ctx, std::vector<uint64_t>(tableSize, 0), "cell keys");
  pass.bind(shared::BINDING_RAY_ORIGIN, p);
  pass.bind(shared::BINDING_RAY_DIRECTION, nb);
  pass.bind(shared::BINDING_RNG, slots);
  pass.bind(shared::BINDING_CELL_KEYS, keys);
  shared::CellLookupConstants pc{};
  pc.pointCount = n;
  pc.gridOrigin = glm::vec3(0.0f);
  pc.gridInvCellSize = 1.0f;
  pc.cellTableSize = tableSize;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    pass.dispatch(cmd, &pc, sizeof(pc), workgroupsFor(n));
  });
  std::vector<uint32_t> got = slots.downloadAll<uint32_t>();
  std::vector<uint64_t> table = keys.downloadAll<uint64_t>();
  std::map<int, uint32_t> slotOfCell;
  std::map<uint32_t, int> cellOfSlot;
  for (uint32_t i = 0; i < n; ++i) {
    ASSERT_NE(got[i], shared::kNoCell) << "the table has room for every cell";
    auto [it, inserted] = slotOfCell.emplace(cellOf[i], got[i]);
    ASSERT_EQ(it->second, got[i]) << "one cell, one slot";
    auto [jt, inserted2] = cellOfSlot.emplace(got[i], cellOf[i]);
    ASSERT_EQ(jt->second, cellOf[i]) << "one slot, one cell";
    // The key the C++ build computes is the key the GPU stored in that slot.
    EXPECT_EQ(table[got[i]], shared::cellKey(shared::CellGrid{glm::vec3(0.0f), 1.0f, tableSize, 0, 0, 0}, positions[i], normals[i], materials[i]));
  }
  EXPECT_EQ(slotOfCell.size(), 500u);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}
