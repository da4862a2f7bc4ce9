// The BVH traversal as the GPU runs it (shaders/tests/trace_rays.comp, the same shared header
// the intersect and shadow stages include) against brute force over all triangles, on random
// triangle soups and on the shipped scenes. Also reports GPU rays per second (not asserted).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "bvh/bvh.h"
#include "gltf/gltf_loader.h"
#include "shared/bindings.h"
#include "tests/trace_rays_interface.h"
#include "support/shipped_scenes.h"
#include "shared/layouts.h"
#include "vulkan/buffer.h"
#include "vulkan/context.h"
#include "vulkan/compute_pass.h"

using namespace mixtrace;
namespace fs = std::filesystem;

namespace {

struct Ray {
  glm::vec3 origin, direction;
};

// Möller-Trumbore in double precision: the reference the float traversal is held to.
bool intersectExact(const Triangle& t, const Ray& r, double* tHit) {
  glm::dvec3 o(r.origin), d(r.direction), v0(t.p[0]), e1 = glm::dvec3(t.p[1]) - v0, e2 = glm::dvec3(t.p[2]) - v0;
  glm::dvec3 p = glm::cross(d, e2);
  double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return false;
  double inv = 1.0 / det;
  glm::dvec3 s = o - v0;
  double u = glm::dot(s, p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  glm::dvec3 q = glm::cross(s, e1);
  double v = glm::dot(d, q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  double tt = glm::dot(e2, q) * inv;
  if (!(tt > 0.0)) return false;
  *tHit = tt;
  return true;
}

double bruteForceClosest(const std::vector<Triangle>& tris, const Ray& r) {
  double best = INFINITY;
  for (const Triangle& t : tris) {
    double th;
    if (intersectExact(t, r, &th) && th < best) best = th;
  }
  return best;
}

class GpuTracer {
 public:
  GpuTracer(VulkanContext& ctx, const Bvh& bvh)
      : ctx_(ctx), nodes_(makeBuffer(ctx, bvh.nodes, "nodes")), tris_(makeBuffer(ctx, bvh.triangles, "triangles")),
        pass_(ctx, "trace_rays", BINDINGS_OF(TRACE_RAYS_BUFFERS), sizeof(shared::TraceRaysConstants), {}) {
    pass_.bind(shared::BINDING_BVH_NODES, nodes_);
    pass_.bind(shared::BINDING_TRIANGLES, tris_);
  }

  // Closest hits; also returns the seconds the dispatch took (wall clock around the submit).
  std::vector<shared::HitRecord> closest(const std::vector<Ray>& rays, double* seconds = nullptr) {
    std::vector<glm::vec3> o, d;
    for (auto& r : rays) { o.push_back(r.origin); d.push_back(r.direction); }
    Buffer ob = makeBuffer(ctx_, o, "o"), db = makeBuffer(ctx_, d, "d");
    Buffer hb(ctx_, rays.size() * sizeof(shared::HitRecord), "hits");
    pass_.bind(shared::BINDING_RAY_ORIGIN, ob);
    pass_.bind(shared::BINDING_RAY_DIRECTION, db);
    pass_.bind(shared::BINDING_HITS, hb);
    pass_.bind(shared::BINDING_MIS_PDF, hb);
    run(uint32_t(rays.size()), 0, seconds);
    return hb.downloadAll<shared::HitRecord>();
  }

  std::vector<float> any(const std::vector<Ray>& rays, const std::vector<float>& tMax) {
    std::vector<glm::vec3> o, d;
    for (auto& r : rays) { o.push_back(r.origin); d.push_back(r.direction); }
    Buffer ob = makeBuffer(ctx_, o, "o"), db = makeBuffer(ctx_, d, "d"), tb = makeBuffer(ctx_, tMax, "t");
    pass_.bind(shared::BINDING_RAY_ORIGIN, ob);
    pass_.bind(shared::BINDING_RAY_DIRECTION, db);
    pass_.bind(shared::BINDING_MIS_PDF, tb);
    pass_.bind(shared::BINDING_HITS, tb);
    run(uint32_t(rays.size()), 1, nullptr);
    return tb.downloadAll<float>();
  }

 private:
  void run(uint32_t n, uint32_t mode, double* seconds) {
    shared::TraceRaysConstants pc{};
    pc.rayCount = n;
    pc.mode = mode;
    auto start = std::chrono::steady_clock::now();
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
      pass_.dispatch(cmd, &pc, sizeof(pc), workgroupsFor(n));
    });
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  VulkanContext& ctx_;
  Buffer nodes_, tris_;
  ComputePass pass_;
};

std::vector<Ray> randomRays(const Bounds& b, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  glm::vec3 lo = b.min - 0.25f * b.extent(), size = 1.5f * b.extent();
  std::vector<Ray> rays(n);
  for (size_t i = 0; i < n; ++i) {
    rays[i].origin = lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
    glm::vec3 target = b.min + glm::vec3(u(rng), u(rng), u(rng)) * b.extent();
    glm::vec3 d = target - rays[i].origin;
    if (i % 7 == 0) d = glm::vec3(i % 3 == 0 ? 1.0f : 0.0f, i % 3 == 1 ? -1.0f : 0.0f, i % 3 == 2 ? 1.0f : 0.0f);  // axis-aligned
    if (glm::length(d) == 0.0f) d = glm::vec3(0, 0, 1);
    rays[i].direction = glm::normalize(d);
  }
  return rays;
}

// Compares GPU closest and any hits with brute force. Tolerates disagreements only on rays that
// graze an edge within float precision (hit in one, missed in the other, at a relative 1e-4).
void checkScene(VulkanContext& ctx, const std::vector<Triangle>& tris, const Bounds& bounds, size_t rayCount, const char* label) {
  Bvh bvh = buildBvh(cornersOf(tris));
  GpuTracer tracer(ctx, bvh);
  std::vector<Ray> rays = randomRays(bounds, rayCount, 1234);
  double seconds = 0.0;
  std::vector<shared::HitRecord> hits = tracer.closest(rays, &seconds);
  size_t mismatches = 0, hitCount = 0;
  std::vector<float> tMax(rays.size());
  std::vector<double> reference(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    reference[i] = bruteForceClosest(tris, rays[i]);
    bool refHit = std::isfinite(reference[i]);
    bool gpuHit = hits[i].triangle != shared::kNoHit;
    hitCount += refHit;
    if (refHit != gpuHit) ++mismatches;
    else if (refHit && std::abs(hits[i].t - reference[i]) > 1e-4 * std::max(1.0, reference[i])) ++mismatches;
    // Any-hit queries just before and just after the closest hit.
    tMax[i] = refHit ? float(reference[i] * ((i & 1) ? 0.999 : 1.001)) : 1e30f;
  }
  std::vector<float> blocked = tracer.any(rays, tMax);
  size_t anyMismatches = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    bool expectBlocked = std::isfinite(reference[i]) && (i & 1) == 0;
    if ((blocked[i] > 0.5f) != expectBlocked) ++anyMismatches;
  }
  std::printf("[%s] %zu triangles, %zu rays (%zu hit): %.2f M closest-hit rays/s on %s\n", label, tris.size(), rays.size(),
              hitCount, rays.size() / seconds * 1e-6, ctx.deviceName().c_str());
  EXPECT_GT(hitCount, rays.size() / 10) << label << ": the ray set should hit something";
  EXPECT_LE(mismatches, rays.size() / 2000) << label;
  EXPECT_LE(anyMismatches, rays.size() / 2000) << label;
}

std::vector<Triangle> randomSoup(size_t n, float scale, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Triangle> tris(n);
  for (auto& t : tris) {
    glm::vec3 c = glm::vec3(u(rng), u(rng), u(rng)) * scale;
    float size = scale * 0.05f * (0.1f + u(rng));
    for (int k = 0; k < 3; ++k) t.p[k] = c + (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f) * size;
    t.material = 0;
    t.primitive = 0;
  }
  return tris;
}

Bounds boundsOf(const std::vector<Triangle>& tris) {
  Bounds b;
  for (auto& t : tris)
    for (auto& p : t.p) b.grow(p);
  return b;
}

}  // namespace

TEST(GpuBvh, RandomSoupMatchesBruteForce) {
  VulkanContext ctx(ContextOptions{"", true});
  for (float scale : {1.0f, 1e-3f, 1e3f}) {
    auto tris = randomSoup(3000, scale, 42);
    checkScene(ctx, tris, boundsOf(tris), 4000, scale == 1.0f ? "soup" : (scale < 1.0f ? "soup 1e-3" : "soup 1e3"));
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

TEST(GpuBvh, ShippedScenesMatchBruteForce) {
  VulkanContext ctx(ContextOptions{"", true});
  for (const std::string& path : mixtrace::testing::shippedScenes()) {
    Scene scene = loadGltf(path);
    checkScene(ctx, scene.triangles, scene.bounds, 3000, scene.name.c_str());
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}
