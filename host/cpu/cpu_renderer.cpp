#include "cpu/cpu_renderer.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <thread>

#include "cpu/cpu_cms_path.h"
#include "cpu/cpu_kernel_access.h"
#include "shared/first_hit_aov.h"   // after the kernel access: it reads the scene through its macros
#include "shared/path_tracer.h"     // likewise
#include "util/error.h"
#include "shared/bsdf.h"
#include "shared/scatter_side.h"
#include "shared/camera.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"

namespace mixtrace {
namespace {

constexpr uint32_t kTileSize = 16;

}  // namespace

CpuRenderer::CpuRenderer(const PreparedScene& scene, const MethodLights& lights, const RenderSettings& settings)
    : scene_(scene),
      lights_(lights),
      settings_(settings),
      camera_(makeCamera(scene.scene, settings.width, settings.height)),
      lightCount_(uint32_t(scene.lights.lights.size())),
      threads_(settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency())),
      film_(size_t(settings.width) * settings.height),
      aovs_(settings.aovs ? shared::kAovStride * size_t(settings.width) * settings.height : 0, glm::dvec3(0.0)) {
  if (settings.maxDepth < 1) throw Error("--max-depth must be at least 1");
  if (lights.selection.size() != lightCount_) throw Error("internal: a light selection table of another scene");
  setUpTraining(settings);
  if (settings.cms.clusters && !lights.cms.clusters.clusters.empty())
    cms_ = std::make_unique<CpuCmsCells>(lights.cms, scene.scene.bounds, settings, uint32_t(film_.size()));
  kernel_.scene = &scene_;
  kernel_.lightSelection = &lights_.selection;
  kernel_.lightBvh = &lights_.bvh;
  kernel_.uniformEmitters = lights_.kind == LightSelection::Uniform;
  kernel_.cms = cms_.get();
}

std::string CpuRenderer::deviceName() const {
  return "CPU reference (" + std::to_string(threads_) + " threads)";
}

void CpuRenderer::renderTile(uint32_t tile, uint32_t count, RenderCounters& local) {
  const uint32_t tilesX = (settings_.width + kTileSize - 1) / kTileSize;
  const uint32_t x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
  const uint32_t x1 = std::min(x0 + kTileSize, settings_.width), y1 = std::min(y0 + kTileSize, settings_.height);
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      const uint32_t pixel = y * settings_.width + x;
      PixelStats& stats = film_[pixel];
      for (uint32_t s = 0; s < count; ++s) {
        const uint32_t sampleIndex = spp_ + s;
        uint32_t rng = shared::rngInit(pixel, sampleIndex, settings_.seed);
        float jitterX = shared::rngNextFloat(rng);
        float jitterY = shared::rngNextFloat(rng);
        glm::vec2 jitter(jitterX, jitterY);
        glm::vec3 direction = shared::cameraRayDirection(camera_, x, y, jitter);
        if (!aovs_.empty()) {
          // The camera ray's first hit again (the path tracer does not hand it out): what the
          // Vulkan AOV pass reads from the intersect pass's hits.
          const shared::FirstHitAov a = shared::firstHitAov(shared::traceClosest(camera_.position, direction, shared::kFloatMax), direction);
          glm::dvec3* out = &aovs_[shared::kAovStride * pixel];
          const double w = 1.0 / (double(sampleIndex) + 1.0);
          out[shared::kAovAlbedo] += (glm::dvec3(a.albedo) - out[shared::kAovAlbedo]) * w;
          out[shared::kAovNormal] += (glm::dvec3(a.normal) - out[shared::kAovNormal]) * w;
          out[shared::kAovDepth] += (glm::dvec3(a.depth) - out[shared::kAovDepth]) * w;
        }
        glm::vec3 l;
        if (cms_) {
          CmsPathContext ctx;
          ctx.cells = cms_.get();
          ctx.maxDepth = settings_.maxDepth;
          ctx.lightCount = lightCount_;
          ctx.pixel = pixel;
          l = traceCmsPath(camera_.position, direction, rng, ctx, local);
        } else {
          shared::PathCounters rays{0u, 0u};
          l = shared::tracePath(camera_.position, direction, rng, settings_.maxDepth, lightCount_, rays);
          local.extensionRays += rays.extensionRays;
          local.shadowRays += rays.shadowRays;
        }
        if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z)) {
          ++local.nonFiniteSamples;
          l = glm::vec3(0.0f);
        }
        const double n = double(sampleIndex) + 1.0;
        for (int c = 0; c < 3; ++c) {
          double delta = double(l[c]) - stats.mean[c];
          stats.mean[c] += delta / n;
          stats.m2[c] += delta * (double(l[c]) - stats.mean[c]);
        }
      }
    }
}

void CpuRenderer::renderSamples(uint32_t count) {
  if (!cms_) {
    renderPass(count);
    spp_ += count;
    return;
  }
  for (uint32_t s = 0; s < count; ++s) {
    const bool gathering = schedule_.gathers(spp_);
    cms_->setGathering(gathering);
    counters_.gatheringSamples += gathering;
    renderPass(1);
    spp_ += 1;
    // Training iterations of doubling length (docs/estimator.md §7; cms/training_schedule.h): the
    // cells are solved, then the pixel estimate of the relative weights is refreshed.
    if (schedule_.solvesAfter(spp_)) {
      cms_->solveAll();
      if (settings_.relativeWeighting) cms_->refreshPixelEstimate(filmMeans(), settings_.width, settings_.height);
    }
  }
}

std::vector<glm::vec3> CpuRenderer::filmMeans() const {
  std::vector<glm::vec3> means(film_.size());
  for (size_t p = 0; p < film_.size(); ++p)
    means[p] = glm::vec3(float(film_[p].mean[0]), float(film_[p].mean[1]), float(film_[p].mean[2]));
  return means;
}

void CpuRenderer::renderPass(uint32_t count) {
  const uint32_t tiles = ((settings_.width + kTileSize - 1) / kTileSize) * ((settings_.height + kTileSize - 1) / kTileSize);
  std::atomic<uint32_t> nextTile{0};
  std::mutex merge;
  auto worker = [&] {
    CpuKernelBinding bind(kernel_);   // what the shared headers read on this thread
    RenderCounters local;
    for (uint32_t t = nextTile++; t < tiles; t = nextTile++) renderTile(t, count, local);
    std::lock_guard<std::mutex> lock(merge);
    counters_.nonFiniteSamples += local.nonFiniteSamples;
    counters_.extensionRays += local.extensionRays;
    counters_.shadowRays += local.shadowRays;
  };
  std::vector<std::thread> pool;
  for (uint32_t i = 1; i < threads_; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

Image CpuRenderer::readImage(Image* standardError) const {
  Image mean(int(settings_.width), int(settings_.height));
  if (standardError) *standardError = Image(int(settings_.width), int(settings_.height));
  const double n = spp_;
  // M2 in double holds the square of any float image; its square root is back in float range.
  for (size_t p = 0; p < film_.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      mean.rgb[3 * p + c] = float(film_[p].mean[c]);
      if (standardError && spp_ > 1)
        standardError->rgb[3 * p + c] = float(std::sqrt(film_[p].m2[c] / (n * (n - 1.0))));
    }
  return mean;
}

AovImages CpuRenderer::readAovs() const {
  return aovs_.empty() ? AovImages{} : aovImagesFrom(aovs_, settings_.width, settings_.height);
}

RenderCounters CpuRenderer::counters() const {
  RenderCounters c = counters_;
  if (cms_) {
    c.cellsUsed = cms_->cellsUsed();
    c.cellTableSize = cms_->grid().tableSize;
    c.verticesWithoutCell = cms_->verticesWithoutCell();
    cms_->reportPairs(c);
  }
  return c;
}

}  // namespace mixtrace
