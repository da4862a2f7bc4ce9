// The (cell, technique) pair table (shaders/shared/cms_pair_table.h): one slot per distinct pair
// under the GPU's concurrent compare-and-swap insertion, lookups that find what was inserted, a
// full table that refuses new pairs without disturbing the old ones, the C++ build (std::atomic)
// agreeing slot for slot with the GPU, and a table of 10,000 techniques x 256 cells.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "shared/cms_pair_layout.h"
#include "tests/pair_lookup_interface.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pass.h"
#include "vulkan/context.h"

namespace {
std::vector<std::atomic<uint64_t>>* gPairKeys = nullptr;
uint64_t casPairKey(uint32_t slot, uint64_t expected, uint64_t desired) {
  (*gPairKeys)[slot].compare_exchange_strong(expected, desired);
  return expected;  // the previous value, as GLSL's atomicCompSwap returns it
}
// The occupied list as the renderers keep it: count first, then the slots in claim order.
std::vector<std::atomic<uint32_t>>* gOccupied = nullptr;
void claimSlot(uint32_t slot) {
  (*gOccupied)[mixtrace::shared::kPairOccupiedFirst + (*gOccupied)[mixtrace::shared::kPairOccupiedCount].fetch_add(1)] = slot;
}
}  // namespace

#define PAIR_KEY_LOAD(slot) ((*gPairKeys)[slot].load())
#define PAIR_KEY_CAS(slot, expected, desired) casPairKey(slot, expected, desired)
#define PAIR_SLOT_CLAIMED(slot) claimSlot(slot)
#define PAIR_OCCUPIED_COUNT() ((*gOccupied)[mixtrace::shared::kPairOccupiedCount].load())
#include "shared/cms_pair_table.h"

using namespace mixtrace;
using shared::kNoPairSlot;

namespace {

using Pair = glm::uvec2;  // (cell, technique)

struct CpuTable {
  explicit CpuTable(size_t capacity) : keys(capacity), occupiedList(capacity + shared::kPairOccupiedFirst) {
    for (auto& k : keys) k = 0;
    for (auto& o : occupiedList) o = 0;
    gPairKeys = &keys;
    gOccupied = &occupiedList;
  }
  std::vector<uint64_t> snapshot() const {
    std::vector<uint64_t> s;
    for (const auto& k : keys) s.push_back(k.load());
    return s;
  }
  std::vector<uint32_t> occupiedSnapshot() const {
    std::vector<uint32_t> s;
    for (const auto& o : occupiedList) s.push_back(o.load());
    return s;
  }
  std::vector<std::atomic<uint64_t>> keys;
  std::vector<std::atomic<uint32_t>> occupiedList;
};

// The GPU's table: the key array stays on the device between dispatches.
class GpuTable {
 public:
  explicit GpuTable(uint32_t capacity)
      : ctx_(ContextOptions{"", true}),
        pass_(ctx_, "pair_lookup", BINDINGS_OF(PAIR_LOOKUP_BUFFERS), sizeof(shared::PairLookupConstants), {}),
        capacity_(capacity),
        keys_(makeBuffer(ctx_, std::vector<uint64_t>(capacity, 0), "pair keys")),
        occupied_(makeBuffer(ctx_, std::vector<uint32_t>(capacity + shared::kPairOccupiedFirst, 0), "occupied slots")) {}

  // Each query's slot (or kNoPairSlot), all queries at once (or in order, by one invocation).
  std::vector<uint32_t> run(const std::vector<Pair>& queries, uint32_t mode) {
    Buffer q = makeBuffer(ctx_, queries, "pair queries");
    Buffer slots = makeBuffer(ctx_, std::vector<uint32_t>(queries.size(), 0xdeadbeefu), "pair slots");
    pass_.bind(shared::BINDING_PAIR_QUERIES, q);
    pass_.bind(shared::BINDING_PAIR_SLOTS, slots);
    pass_.bind(shared::BINDING_PAIR_LOOKUP_KEYS, keys_);
    pass_.bind(shared::BINDING_PAIR_LOOKUP_OCCUPIED, occupied_);
    shared::PairLookupConstants pc{};
    pc.queryCount = uint32_t(queries.size());
    pc.capacity = capacity_;
    pc.mode = mode;
    const uint32_t groups = mode == shared::kPairLookupInsertInOrder ? 1u : workgroupsFor(pc.queryCount);
    const auto start = std::chrono::steady_clock::now();
    ctx_.submitAndWait([&](VkCommandBuffer cmd) { pass_.dispatch(cmd, &pc, sizeof(pc), groups); });
    lastSubmitSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return slots.downloadAll<uint32_t>();
  }
  std::vector<uint64_t> keys() const { return keys_.downloadAll<uint64_t>(); }
  std::vector<uint32_t> occupiedList() const {   // the buffer may be rounded up: its first entries
    std::vector<uint32_t> list = occupied_.downloadAll<uint32_t>();
    list.resize(capacity_ + shared::kPairOccupiedFirst);
    return list;
  }
  size_t validationErrors() const { return ctx_.validationErrors(); }
  uint64_t maxStorageBufferRange() const { return ctx_.maxStorageBufferRange(); }
  double lastSubmitSeconds() const { return lastSubmitSeconds_; }  // the dispatch alone

 private:
  VulkanContext ctx_;
  ComputePass pass_;
  uint32_t capacity_;
  Buffer keys_;
  Buffer occupied_;
  double lastSubmitSeconds_ = 0.0;
};

// Every accepted query got the slot of its pair, no two pairs share a slot, and the key the C++
// build computes is the one in that slot. Returns the number of distinct pairs with a slot.
size_t expectOneSlotPerPair(const std::vector<Pair>& queries, const std::vector<uint32_t>& slots,
                            const std::vector<uint64_t>& keys) {
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> slotOfPair;
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> pairOfSlot;
  for (size_t i = 0; i < queries.size(); ++i) {
    if (slots[i] == kNoPairSlot) continue;
    const std::pair<uint32_t, uint32_t> p{queries[i].x, queries[i].y};
    EXPECT_LT(slots[i], keys.size());
    if (slots[i] >= keys.size()) return 0;
    auto [it, fresh] = slotOfPair.emplace(p, slots[i]);
    EXPECT_EQ(it->second, slots[i]) << "one pair, one slot";
    auto [jt, fresh2] = pairOfSlot.emplace(slots[i], p);
    EXPECT_EQ(jt->second, p) << "one slot, one pair";
    EXPECT_EQ(keys[slots[i]], shared::pairKey(p.first, p.second));
  }
  return slotOfPair.size();
}

size_t occupied(const std::vector<uint64_t>& keys) {
  return size_t(std::count_if(keys.begin(), keys.end(), [](uint64_t k) { return k != 0; }));
}

// The occupied list (count, then slots) names exactly the slots whose key is set, each once: what
// the sparse solve walks instead of the table.
void expectOccupiedListMatchesKeys(const std::vector<uint32_t>& list, const std::vector<uint64_t>& keys) {
  ASSERT_EQ(list.size(), keys.size() + shared::kPairOccupiedFirst);
  const uint32_t count = list[shared::kPairOccupiedCount];
  EXPECT_EQ(count, occupied(keys)) << "one entry per claimed slot";
  ASSERT_LE(count, keys.size());
  std::vector<uint32_t> listed(list.begin() + shared::kPairOccupiedFirst, list.begin() + shared::kPairOccupiedFirst + count);
  std::sort(listed.begin(), listed.end());
  std::vector<uint32_t> set;
  for (uint32_t slot = 0; slot < keys.size(); ++slot)
    if (keys[slot] != 0) set.push_back(slot);
  EXPECT_EQ(listed, set) << "the list holds every occupied slot, once";
}

}  // namespace

TEST(CmsPairTable, KeysNameTheirPairAndAreNeverEmpty) {
  EXPECT_NE(shared::pairKey(0, 0), uint64_t(0));
  EXPECT_NE(shared::pairKey(0, 1), shared::pairKey(1, 0));
  EXPECT_EQ(shared::pairKeyCell(shared::pairKey(0xfffffffeu, 7)), 0xfffffffeu);
  EXPECT_EQ(shared::pairKeyTechnique(shared::pairKey(3, 0xffffffffu)), 0xffffffffu);
  CpuTable t(16);
  EXPECT_EQ(shared::findOrInsertPair(16, shared::kNoCell, 0), kNoPairSlot) << "a vertex without a cell has no pair";
  EXPECT_EQ(shared::findPair(16, 2, 3), kNoPairSlot) << "an empty table holds nothing";
  uint32_t s = shared::findOrInsertPair(16, 2, 3);
  EXPECT_NE(s, kNoPairSlot);
  EXPECT_EQ(shared::findPair(16, 2, 3), s);
  EXPECT_EQ(shared::findOrInsertPair(16, 2, 3), s);
}

TEST(CmsPairTable, CapacityKeepsTheLoadAtMostHalfAndFitsOneStorageBuffer) {
  EXPECT_EQ(shared::pairTableCapacityFor(0), 1u);
  EXPECT_EQ(shared::pairTableCapacityFor(1), 2u);
  EXPECT_EQ(shared::pairTableCapacityFor(1000), 2048u);
  EXPECT_EQ(shared::pairTableCapacityFor(1024), 2048u);
  EXPECT_EQ(shared::pairTableCapacityFor(1025), 4096u);
  EXPECT_EQ(shared::pairTableCapacityFor(0xffffffffu), 1u << shared::kMaxPairTableLog2) << "clamped, no overflow";
  // lavapipe's maxStorageBufferRange is 128 MiB: the largest table's biggest array must fit it.
  constexpr uint64_t kLavapipeRange = 128ull << 20;
  const uint64_t largest = uint64_t(1) << shared::kMaxPairTableLog2;
  EXPECT_LE(largest * shared::kPairStatsBytes, kLavapipeRange);
  EXPECT_GT(2 * largest * shared::kPairStatsBytes, kLavapipeRange) << "the bound is tight";
  EXPECT_EQ(shared::kPairBytesPerSlot, shared::kPairKeyBytes + shared::kPairStatsBytes + shared::kPairCountBytes);
  EXPECT_EQ(shared::pairStatsBt(3, 2) + 1, shared::pairStatsAtt(4)) << "the five floats of a slot are contiguous";
}

// A cell's consecutive techniques (neighbouring triangles of one light, which a vertex's samples
// reach together) share cache lines: in an empty table a run of kPairRunLength of them takes
// consecutive slots. Runs are hashed apart, so filling a table to half its capacity with whole
// cells of many techniques refuses nothing (a probe that starts inside another run leaves it).
TEST(CmsPairTable, ConsecutiveTechniquesOfACellShareCacheLines) {
  const uint32_t capacity = 1u << 16;
  {
    CpuTable t(capacity);
    const uint32_t first = shared::findOrInsertPair(capacity, 5, 3 * shared::kPairRunLength);
    for (uint32_t i = 1; i < shared::kPairRunLength; ++i)
      EXPECT_EQ(shared::findOrInsertPair(capacity, 5, 3 * shared::kPairRunLength + i), (first + i) & (capacity - 1)) << i;
    EXPECT_NE(shared::findOrInsertPair(capacity, 5, 4 * shared::kPairRunLength), (first + shared::kPairRunLength) & (capacity - 1))
        << "the next run starts elsewhere";
  }
  CpuTable t(capacity);
  uint32_t refused = 0;
  for (uint32_t cell = 0; cell < capacity / 2 / 2048; ++cell)
    for (uint32_t technique = 0; technique < 2048; ++technique)
      refused += shared::findOrInsertPair(capacity, cell, technique) == kNoPairSlot;
  EXPECT_EQ(refused, 0u);
  expectOccupiedListMatchesKeys(t.occupiedSnapshot(), t.snapshot());
}

// (c) on the C++ build: a table of 16 slots takes exactly 12 triangle pairs (three quarters, the
// rest kept for remainder pairs: shared/cms_pair_layout.h pairTriangleSlotLimit), refuses the
// others, and still finds the first 12; remainder pairs then take exactly the 4 slots left (the
// probe sequence reaches every slot).
TEST(CmsPairTable, FullTableRefusesNewPairsAndKeepsOldOnes) {
  CpuTable t(16);
  ASSERT_EQ(shared::pairTriangleSlotLimit(16), 12u);
  EXPECT_EQ(shared::findOrInsertPair(16, 0, shared::remainderTechnique(1)), kNoPairSlot)
      << "no remainder pair below the triangle pairs' limit";
  EXPECT_FALSE(shared::remaindersMayExist(16));
  std::vector<uint32_t> slots;
  int refused = 0;
  for (uint32_t i = 0; i < 100; ++i) {
    uint32_t s = shared::findOrInsertPair(16, i / 10, i % 10);
    slots.push_back(s);
    if (s == kNoPairSlot) ++refused;
  }
  EXPECT_EQ(refused, 100 - 12) << "three quarters of the slots are used before a triangle pair is refused";
  EXPECT_EQ(occupied(t.snapshot()), 12u);
  EXPECT_TRUE(shared::remaindersMayExist(16));
  int remainders = 0;
  for (uint32_t cell = 0; cell < 10; ++cell) remainders += shared::findOrInsertPair(16, cell, shared::remainderTechnique(1)) != kNoPairSlot;
  EXPECT_EQ(remainders, 4) << "remainder pairs take the slots kept for them";
  const std::vector<uint64_t> full = t.snapshot();
  EXPECT_EQ(occupied(full), 16u);
  for (uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(shared::findPair(16, i / 10, i % 10), slots[i]) << i;
    EXPECT_EQ(shared::findOrInsertPair(16, i / 10, i % 10), slots[i]) << i;
  }
  EXPECT_EQ(t.snapshot(), full) << "nothing overwritten";
  expectOccupiedListMatchesKeys(t.occupiedSnapshot(), full);
}

// The C++ binding is as safe under contention as the GPU's: 8 threads each insert all 1500 pairs
// (8 times over, in an order of their own), so every pair is raced for; all agree on its slot.
TEST(CmsPairTable, CppInsertionIsConsistentUnderContention) {
  const uint32_t capacity = 4096, threadCount = 8;
  CpuTable t(capacity);
  std::vector<Pair> pairs;
  for (uint32_t i = 0; i < 1500; ++i) pairs.push_back(Pair(i % 37, i * 7));
  std::vector<std::vector<Pair>> queries(threadCount);
  std::vector<std::vector<uint32_t>> slots(threadCount);
  for (uint32_t k = 0; k < threadCount; ++k) {
    for (uint32_t rep = 0; rep < 8; ++rep) queries[k].insert(queries[k].end(), pairs.begin(), pairs.end());
    std::shuffle(queries[k].begin(), queries[k].end(), std::mt19937(k));
    slots[k].resize(queries[k].size());
  }
  std::atomic<uint32_t> ready{0};
  std::vector<std::thread> threads;
  for (uint32_t k = 0; k < threadCount; ++k)
    threads.emplace_back([&, k] {
      ready.fetch_add(1);
      while (ready.load() < threadCount) std::this_thread::yield();  // start together
      for (size_t i = 0; i < queries[k].size(); ++i)
        slots[k][i] = shared::findOrInsertPair(capacity, queries[k][i].x, queries[k][i].y);
    });
  for (auto& th : threads) th.join();
  std::vector<Pair> allQueries;
  std::vector<uint32_t> allSlots;
  for (uint32_t k = 0; k < threadCount; ++k) {
    allQueries.insert(allQueries.end(), queries[k].begin(), queries[k].end());
    allSlots.insert(allSlots.end(), slots[k].begin(), slots[k].end());
  }
  const std::vector<uint64_t> keys = t.snapshot();
  EXPECT_EQ(std::count(allSlots.begin(), allSlots.end(), kNoPairSlot), 0);
  EXPECT_EQ(expectOneSlotPerPair(allQueries, allSlots, keys), 1500u);
  EXPECT_EQ(occupied(keys), 1500u);
  expectOccupiedListMatchesKeys(t.occupiedSnapshot(), keys);
}

// (a) + (b): 65536 invocations insert 3000 distinct pairs (about 22 racing for each) at once;
// every pair gets one slot, and a lookup pass finds the same slots, and nothing for absent pairs.
TEST(CmsPairTable, GpuInsertionGivesEveryPairOneSlotAndLookupsFindIt) {
  const uint32_t n = 65536, distinct = 3000, capacity = 8192;
  std::mt19937 rng(11);
  std::uniform_int_distribution<uint32_t> technique(0, 9999), pick(0, distinct - 1);
  std::set<std::pair<uint32_t, uint32_t>> chosen;
  std::vector<Pair> pairs;
  while (pairs.size() < distinct) {
    Pair p(uint32_t(pairs.size()) % 60, technique(rng));  // 60 cells, techniques among 10,000
    if (chosen.insert({p.x, p.y}).second) pairs.push_back(p);
  }
  std::vector<Pair> queries(n);
  for (uint32_t i = 0; i < n; ++i) queries[i] = i < distinct ? pairs[i] : pairs[pick(rng)];
  std::shuffle(queries.begin(), queries.end(), rng);

  GpuTable gpu(capacity);
  const std::vector<uint32_t> inserted = gpu.run(queries, shared::kPairLookupInsert);
  const std::vector<uint64_t> keys = gpu.keys();
  EXPECT_EQ(std::count(inserted.begin(), inserted.end(), kNoPairSlot), 0) << "the table has room for every pair";
  EXPECT_EQ(expectOneSlotPerPair(queries, inserted, keys), size_t(distinct));
  EXPECT_EQ(occupied(keys), size_t(distinct)) << "no slot claimed twice or for nothing";
  expectOccupiedListMatchesKeys(gpu.occupiedList(), keys);

  // Lookups: the same queries, then pairs never inserted (techniques beyond 10,000, a new cell).
  EXPECT_EQ(gpu.run(queries, shared::kPairLookupFind), inserted);
  std::vector<Pair> absent;
  for (uint32_t i = 0; i < 2000; ++i) absent.push_back(Pair(i % 61, 10000 + i));
  const std::vector<uint32_t> missing = gpu.run(absent, shared::kPairLookupFind);
  EXPECT_EQ(std::count(missing.begin(), missing.end(), kNoPairSlot), 2000);
  EXPECT_EQ(gpu.keys(), keys) << "lookups insert nothing";
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

// (c) on the GPU: a table of 64 slots, filled, then raced by 4096 invocations inserting 1000 new
// pairs and the 64 old ones: every new pair is refused, every old one found, no key changes.
TEST(CmsPairTable, GpuFullTableRefusesNewPairsAndNeverOverwrites) {
  const uint32_t capacity = 64;
  std::vector<Pair> first;
  for (uint32_t i = 0; i < 200; ++i) first.push_back(Pair(i % 5, i));
  GpuTable gpu(capacity);
  const std::vector<uint32_t> firstSlots = gpu.run(first, shared::kPairLookupInsert);
  const std::vector<uint64_t> full = gpu.keys();
  // At least the triangle pairs' three quarters (a soft bound: invocations that read the count at
  // once may all claim), at most every slot.
  EXPECT_GE(occupied(full), size_t(shared::pairTriangleSlotLimit(capacity)));
  EXPECT_LE(occupied(full), size_t(capacity));
  EXPECT_EQ(expectOneSlotPerPair(first, firstSlots, full), occupied(full));

  std::vector<Pair> kept, queries;
  for (size_t i = 0; i < first.size(); ++i)
    if (firstSlots[i] != kNoPairSlot) kept.push_back(first[i]);
  std::mt19937 rng(2);
  for (uint32_t i = 0; i < 4096; ++i)
    queries.push_back(i % 4 == 0 ? kept[i / 4 % kept.size()] : Pair(7 + i % 3, 1000 + i % 1000));
  std::shuffle(queries.begin(), queries.end(), rng);
  const std::vector<uint32_t> slots = gpu.run(queries, shared::kPairLookupInsert);
  for (size_t i = 0; i < queries.size(); ++i) {
    if (queries[i].x >= 7) {
      EXPECT_EQ(slots[i], kNoPairSlot) << "a new pair in a full table";
    } else {
      ASSERT_NE(slots[i], kNoPairSlot);
      EXPECT_EQ(full[slots[i]], shared::pairKey(queries[i].x, queries[i].y)) << "an old pair keeps its slot";
    }
  }
  EXPECT_EQ(gpu.keys(), full) << "nothing overwritten";
  expectOccupiedListMatchesKeys(gpu.occupiedList(), full);
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

// (d): inserted in one order, by one GPU invocation and by the C++ build, an overfull table (1100
// pairs for 1024 slots, 768 of them for triangle pairs: long probe sequences, then refusals) gives the same slot to every pair and
// the same keys.
TEST(CmsPairTable, CppAndGpuGiveTheSameSlotsInOrder) {
  const uint32_t capacity = 1024;
  std::vector<Pair> queries;
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> cell(0, 40), technique(0, 9999);
  for (uint32_t i = 0; i < 1100; ++i) queries.push_back(Pair(cell(rng), technique(rng)));
  for (uint32_t i = 0; i < 200; ++i) queries.push_back(queries[i * 3]);  // repeats find their slot

  CpuTable cpu(capacity);
  std::vector<uint32_t> cpuSlots;
  for (const Pair& q : queries) cpuSlots.push_back(shared::findOrInsertPair(capacity, q.x, q.y));
  GpuTable gpu(capacity);
  const std::vector<uint32_t> gpuSlots = gpu.run(queries, shared::kPairLookupInsertInOrder);
  EXPECT_EQ(gpuSlots, cpuSlots);
  EXPECT_EQ(gpu.keys(), cpu.snapshot());
  EXPECT_EQ(gpu.occupiedList(), cpu.occupiedSnapshot()) << "in order, the same slots in the same order";
  const auto refused = std::count(cpuSlots.begin(), cpuSlots.end(), kNoPairSlot);
  EXPECT_GE(refused, 1100 - shared::pairTriangleSlotLimit(capacity)) << "the test reaches the triangle pairs' limit";
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

// (e): 10,000 techniques x 256 cells (2.56 M pairs, every one of them sampled) in the table
// pairTableCapacityFor picks (the largest, 2^22: load 0.61), inserted at once, all fit.
TEST(CmsPairTable, TenThousandTechniquesTimesCellsFitAndInsertFast) {
  const uint32_t techniques = 10000, cells = 256, n = techniques * cells;
  const uint32_t capacity = shared::pairTableCapacityFor(n);
  ASSERT_EQ(capacity, 1u << shared::kMaxPairTableLog2);
  std::vector<Pair> queries(n);
  for (uint32_t i = 0; i < n; ++i) queries[i] = Pair(i % cells, i / cells);
  std::shuffle(queries.begin(), queries.end(), std::mt19937(1));

  GpuTable gpu(capacity);
  EXPECT_LE(uint64_t(capacity) * shared::kPairStatsBytes, gpu.maxStorageBufferRange());
  const auto start = std::chrono::steady_clock::now();
  const std::vector<uint32_t> slots = gpu.run(queries, shared::kPairLookupInsert);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("insert_seconds", std::to_string(seconds));
  std::printf("%u pairs into %u slots: %.3f s with upload and readback, %.3f s the dispatch\n", n, capacity, seconds,
              gpu.lastSubmitSeconds());
  EXPECT_EQ(std::count(slots.begin(), slots.end(), kNoPairSlot), 0) << "every pair fits";
  std::vector<uint32_t> sorted = slots;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "distinct pairs, distinct slots";
  const std::vector<uint64_t> keys = gpu.keys();
  size_t wrong = 0;
  for (uint32_t i = 0; i < n; ++i) wrong += keys[slots[i]] != shared::pairKey(queries[i].x, queries[i].y);
  EXPECT_EQ(wrong, 0u);
  expectOccupiedListMatchesKeys(gpu.occupiedList(), keys);
  EXPECT_LT(seconds, 20.0) << "lavapipe on two shared cores";
  EXPECT_EQ(gpu.validationErrors(), 0u);
}
