#pragma once
// What the render command needs from a backend: the Vulkan wavefront renderer
// (wavefront/wavefront_renderer.h) and the CPU reference (cpu/cpu_renderer.h) implement it.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cms/cms_setup.h"
#include "cms/training_schedule.h"
#include "output/image.h"
#include "shared/aov_layout.h"
#include "shared/cms_layouts.h"

namespace mixtrace {

struct RenderSettings {
  uint32_t width = 320;
  uint32_t height = 240;
  uint32_t maxDepth = 5;
  uint32_t seed = 0;
  bool generalPipelines = false;         // Vulkan: ignore the feature set (testing aid)
  // Vulkan: how sample passes are dispatched. Wavefront: a pass per stage and depth; fused: one
  // dispatch that traces whole paths (every method; not with AOVs); auto: the wavefront on GPUs, and
  // on a CPU device fused where the first submission's paths ran deep (wavefront_renderer.cpp).
  enum class Schedule { Auto, Wavefront, Fused } schedule = Schedule::Auto;
  uint32_t maxPathsPerChunk = 1u << 20;  // Vulkan: the wavefront's width; larger images go in chunks
  uint32_t threads = 0;                  // CPU: worker threads, 0 = one per core
  // Controlled mixture sampling (methods learned, cv, cms; docs/estimator.md).
  CmsMethod cms;
  uint32_t cells = 16;           // cells along the scene's longest axis (times 6 normal classes)
  uint32_t minCellSamples = 64;  // a cell's coefficients are trusted from this many vertices on
  float ridge = 1e-3f;           // Tikhonov term of the solve, relative to the scaled diagonal
  float defensive = 0.2f;        // share of the default selection in a learned c_k
  bool relativeWeighting = true; // statistics weighted by throughput relative to the pixel
                                 // (docs/estimator.md §5)
  bool floatAtomics = true;      // Vulkan: float atomics for the statistics where the device has them
  uint32_t trainSpp = 0;         // no solve after this many samples (0 = train through the first half)
  bool trainOnce = false;        // the paper's schedule: one solve after trainSpp (default 16) samples
  // The control variate's coefficients: one per technique of cms/light_techniques.h (an emissive
  // triangle, a group of them beyond the budget, or a punctual light), or one per light cluster
  // (the former per-cluster control variate, kept for comparisons).
  bool perTriangleCv = true;
  bool aovs = false;             // also average the first hit's albedo, normal, depth (--aov)
  uint32_t pairTableSlots = 0;   // the (cell, technique) pair table's slots; 0 = sized for the scene
                                 // (testing aid: a tiny table forces refused pairs)
};

// The parameters of the per-cell CMS solve for these settings (both backends).
inline shared::SolveParams solveParamsFor(const RenderSettings& s, uint32_t cellCount, uint32_t clusters) {
  shared::SolveParams params{};
  params.cellCount = cellCount;
  params.clusterCount = clusters;
  params.minSamples = s.minCellSamples;
  params.flags = (s.cms.learnSelection ? shared::kSolveLearnSelection : 0u) |
                 (s.cms.controlVariate ? shared::kSolveControlVariate : 0u) |
                 (s.cms.defaults == LightSelection::Bvh ? shared::kSolveBvhDefaults : 0u);
  params.ridge = s.ridge;
  params.defensive = s.defensive;
  return params;
}

struct RenderCounters {
  uint64_t nonFiniteSamples = 0;  // NaN/Inf samples caught; they enter the image as 0
  uint64_t extensionRays = 0;
  uint64_t shadowRays = 0;
  uint64_t cellsUsed = 0;             // CMS: cells of the table that vertices fell into
  uint64_t cellTableSize = 0;         // CMS: slots of the table
  uint64_t verticesWithoutCell = 0;   // CMS: vertices refused by a full table (they get no CV)
  std::string statisticsAtomics;      // CMS on Vulkan: "float" atomics or "cas" loops
  std::string schedule;               // Vulkan: "wavefront" or "fused" (what ran)
  std::string shadeQueue;             // Vulkan wavefront: "hits" (shade ran only the rays that hit something) or "rays"
  double autoRayOccupancy = -1.0;     // Vulkan, --schedule auto on a CPU device: the extension rays the first
                                      // submission traced per path and depth, which chose the schedule (-1: none)
  uint32_t gatheringSamples = 0;      // CMS: sample passes that gathered statistics
  // The control variate's techniques (RenderSettings::perTriangleCv): "triangle" or "cluster"
  // (empty: the method has no control variate), and with "triangle" the pair table's use.
  std::string cvTechniques;
  uint64_t techniques = 0;            // techniques (triangle: cms/light_techniques.h; cluster: clusters)
  bool techniquesMerged = false;      // emitters merged into groups to fit --max-techniques
  uint64_t pairTableCapacity = 0;     // slots of the (cell, technique) pair table
  uint64_t pairsUsed = 0;             // slots claimed
  uint64_t pairSamples = 0;           // light-technique samples that found or claimed their pair
  uint64_t pairRefusedSamples = 0;    // ... whose pair and remainder pair the full table refused
  uint64_t pairRemainderSamples = 0;  // ... whose pair it refused, gathered by their cluster's remainder
  uint64_t pairBufferBytes = 0;       // memory of the pair buffers (keys, statistics, counts, alpha)
};

// The first hit's auxiliary images (--aov; shaders/shared/first_hit_aov.h), each RGB: albedo,
// shading normal (x, y, z), depth (the distance in every channel). Empty unless
// RenderSettings::aovs.
struct AovImages {
  Image albedo, normal, depth;
};

// The images from per-pixel running means laid out as shared/aov_layout.h says (kAovStride
// vectors per pixel: the GPU's float buffer, the CPU's doubles).
template <class Vec3>
AovImages aovImagesFrom(const std::vector<Vec3>& means, uint32_t width, uint32_t height) {
  AovImages out;
  out.albedo = out.normal = out.depth = Image(int(width), int(height));
  for (size_t p = 0; p < size_t(width) * height; ++p)
    for (int c = 0; c < 3; ++c) {
      out.albedo.rgb[3 * p + c] = float(means[shared::kAovStride * p + shared::kAovAlbedo][c]);
      out.normal.rgb[3 * p + c] = float(means[shared::kAovStride * p + shared::kAovNormal][c]);
      out.depth.rgb[3 * p + c] = float(means[shared::kAovStride * p + shared::kAovDepth][0]);
    }
  return out;
}

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Renders `count` more samples per pixel; returns when they are done.
  virtual void renderSamples(uint32_t count) = 0;
  virtual uint32_t samplesPerPixel() const = 0;
  // Mean radiance per pixel, and the standard error of that mean when `standardError` is given
  // (not the variance: that would overflow float where the image is above ~1e19, shared/film.h).
  virtual Image readImage(Image* standardError = nullptr) const = 0;
  virtual AovImages readAovs() const = 0;
  virtual RenderCounters counters() const = 0;
  // Time per pass in milliseconds (GPU timestamp queries; empty where there are no passes).
  virtual std::map<std::string, double> passTimesMs() const = 0;
  virtual std::string deviceName() const = 0;
  // Set-up work done inside renderSamples, in seconds: a pipeline built only once the render chose
  // it (the Vulkan renderer's fused kernel under --schedule auto). Counted as set-up, not render time.
  virtual double setupSecondsDuringRender() const { return 0.0; }

  // How many samples per pixel the render will take in all (an estimate for a time-limited one),
  // so the learning methods solve only where an iteration follows and the last iteration gathers
  // no statistics (cms/training_schedule.h). Unplanned renders solve at every boundary.
  void planSamples(uint32_t total) { schedule_.plan(total); }

 protected:
  void setUpTraining(const RenderSettings& s) {
    schedule_.skipFirstSample(s.relativeWeighting);
    if (s.trainOnce)
      schedule_.solveOnceAfter(s.trainSpp != 0 ? s.trainSpp : kPaperTrainingSamples);
    else
      schedule_.limitTraining(s.trainSpp);
  }
  TrainingSchedule schedule_;
};

}  // namespace mixtrace
