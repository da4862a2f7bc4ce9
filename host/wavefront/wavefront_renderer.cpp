#include "wavefront/wavefront_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>

#include "cms/cell_grid.h"
#include "shared/bindings.h"
#include "shared/aov_layout.h"
#include "shared/film.h"
#include "util/error.h"
#include "vulkan/check.h"
#include "vulkan/context.h"
#include "wavefront/passes/sparse_solve_pass.h"

namespace mixtrace {
namespace {

// The least fraction of traced rays that must escape for intersect to go on queueing the hits for
// shade (decideShadeQueue).
constexpr double kShadeQueueMinEscaped = 0.15;

// --schedule auto on a CPU device: the fused schedule once the first submission (the wavefront's)
// traced at least this share of the extension rays its paths could have (one per path and depth).
// The fused kernel runs every bounce's code for all its lanes until the group's last path ends, so
// it wins where paths run to the maximum depth and loses where many end early: on lavapipe, for
// pt-power and cms, fused was faster on indirect_rgb (0.91 of the rays), many_lights (0.89) and
// punctual (0.86) and even or slower on cornell_box (0.57), veach_mis (0.54) and textured (0.45)
// (decideSchedule; benchmarks/README.md, "Speed").
constexpr double kFusedMinRayOccupancy = 0.75;

// A 64-bit counter of QueueState, kept by the GPU as (low, high).
uint64_t counterValue(const uint32_t (&c)[2]) { return uint64_t(c[0]) | (uint64_t(c[1]) << 32); }

// The method's clusters, where it samples lights through them (learned, cv, cms).
const CmsScene* cmsOf(const RenderSettings& s, const MethodLights& lights) {
  return s.cms.clusters ? &lights.cms : nullptr;
}

bool usesCms(const RenderSettings& s, const CmsScene* cms) {
  return s.cms.clusters && cms && !cms->clusters.clusters.empty();
}

uint32_t clustersOf(const RenderSettings& s, const CmsScene* cms) {
  return usesCms(s, cms) ? uint32_t(cms->clusters.clusters.size()) : 1;
}

// Whether the control variate's coefficients are per technique (one per emissive triangle,
// --cv-techniques triangle), as the CPU backend decides it (host/cpu/cpu_cms_cells.cpp).
bool pairTechniquesFor(const RenderSettings& s, const CmsScene* cms) {
  return usesCms(s, cms) && s.cms.controlVariate && s.perTriangleCv && cms->techniques.techniqueCount > 0;
}

BufferExtents extentsFor(const RenderSettings& s, const PreparedScene& scene, const CmsScene* cms, uint32_t paths) {
  BufferExtents e;
  e.paths = paths;
  e.width = s.width;
  e.height = s.height;
  e.cms = usesCms(s, cms);
  e.aovs = s.aovs;
  e.clusters = clustersOf(s, cms);
  e.cellSlots = e.cms ? makeCellGrid(scene.scene.bounds, s.cells, e.clusters).tableSize : 1;
  if (pairTechniquesFor(s, cms)) e.pairSlots = pairTableCapacity(s.pairTableSlots, e.cellSlots, cms->techniques.techniqueCount);
  return e;
}

}  // namespace

bool fusedScheduleRuns(const RenderSettings& s) {
  // The fused schedule keeps a path in registers, for every method (shared/path_tracer.h and
  // shared/cms_path_tracer.h); the first-hit AOVs are the wavefront's aov pass.
  return !s.aovs;
}

WavefrontRenderer::WavefrontRenderer(VulkanContext& ctx, const PreparedScene& scene, const MethodLights& lights,
                                     const RenderSettings& s)
    : ctx_(ctx),
      settings_(s),
      lightCount_(uint32_t(scene.lights.lights.size())),
      pixelCount_(s.width * s.height),
      pathCount_(std::min(s.width * s.height, s.maxPathsPerChunk)),
      scene_(ctx, scene, makeCamera(scene.scene, s.width, s.height)),
      buffers_(ctx, extentsFor(s, scene, cmsOf(s, lights), pathCount_)),
      timer_(ctx, 4096) {
  if (s.maxDepth < 1) throw Error("--max-depth must be at least 1");
  if (lights.selection.size() != lightCount_) throw Error("internal: a light selection table of another scene");
  const CmsScene* cms = cmsOf(s, lights);
  setUpTraining(s);
  // The CMS rows the host uploads (placeholders of one element for the other methods, so every
  // binding is valid).
  const bool useCms = usesCms(s, cms);
  queueForShade_ = !useCms && scene.lights.environmentLight < 0;
  clusterCount_ = clustersOf(s, cms);
  const CellGridSetup grid = makeCellGrid(scene.scene.bounds, s.cells, clusterCount_);
  cellTableSize_ = useCms ? grid.tableSize : 1;
  if (useCms) {
    gridOrigin_ = grid.origin;
    gridInvCellSize_ = grid.invCellSize;
  }
  // The method's light selection, beside the scene's lights (shared/method_buffers.h).
  buffers_.add(shared::BINDING_LIGHT_SELECTION, makeBuffer(ctx, lights.selection, "light selection"));
  lightBvh_ = !lights.bvh.empty();
  // Without a tree (no light to put in one) the BVH's selection is the table's power selection.
  lightSelection_ = lights.kind == LightSelection::Bvh && !lightBvh_ ? LightSelection::Power : lights.kind;
  buffers_.add(shared::BINDING_LIGHT_BVH,
               makeBuffer(ctx, lightBvh_ ? lights.bvh : std::vector<shared::LightBvhNodeGpu>(1), "light BVH"));
  // Padded with zeros to whole texels: the shading passes read it as texels too (shared/cms_state.h).
  std::vector<float> defaults = useCms ? cms->clusters.defaultSelection : std::vector<float>{1.0f};
  defaults.resize(wordsInWholeTexels(defaults.size()), 0.0f);
  buffers_.add(shared::BINDING_CLUSTER_DEFAULTS, makeBuffer(ctx, defaults, "cluster defaults"));
  buffers_.add(shared::BINDING_CLUSTERS,
               makeBuffer(ctx, useCms ? cms->clusters.clusters : std::vector<shared::ClusterGpu>(1), "clusters"));
  buffers_.add(shared::BINDING_CLUSTER_LIGHTS,
               makeBuffer(ctx, useCms ? cms->clusterLights : std::vector<shared::ClusterLightGpu>(1), "cluster lights"));
  // The per-triangle control variate's techniques, by technique source (shared/cms_pair_state.h).
  pairTechniques_ = pairTechniquesFor(s, cms);
  if (pairTechniques_) {
    techniqueCount_ = cms->techniques.techniqueCount;
    emitterCount_ = cms->techniques.emitterCount;
    techniquesMerged_ = cms->techniques.merged();
    pairCapacity_ = pairTableCapacity(s.pairTableSlots, cellTableSize_, techniqueCount_);
  }
  buffers_.add(shared::BINDING_TECHNIQUES,
               makeBuffer(ctx, pairTechniques_ ? cms->techniques.sources : std::vector<shared::TechniqueRefGpu>(1),
                          "CV techniques"));
  buffers_.add(shared::BINDING_TECHNIQUE_CLUSTERS,
               makeBuffer(ctx, pairTechniques_ ? cms->techniques.byTechnique : std::vector<shared::TechniqueClusterGpu>(1),
                          "CV technique clusters"));
  BufferBindings sceneBuffers;
  scene_.offerTo(sceneBuffers);
  bindings_ = buffers_.bindings(sceneBuffers);

  spec_ = (s.generalPipelines ? FeatureSet::general() : scene.features).specialization();
  std::vector<uint32_t>& spec = spec_;
  spec[SPEC_CMS_SELECTION] = useCms;
  spec[SPEC_CMS_CONTROL_VARIATE] = useCms && s.cms.controlVariate;
  spec[SPEC_CMS_RELATIVE_WEIGHT] = useCms && s.relativeWeighting;
  spec[SPEC_CMS_PAIR_TECHNIQUES] = pairTechniques_;
  spec[SPEC_LIGHT_SELECTION] = uint32_t(lightSelection_);
  if (useCms) {
    solver_ = std::make_unique<CellSolver>(ctx);
    solver_->bind(bindings_);
  }
  if (pairTechniques_) {
    sparseSolver_ = std::make_unique<GpuSparseSolver>(ctx);
    sparseSolver_->reserve(cellTableSize_);
    sparseSolver_->bind(bindings_);
  }
  if (useCms && s.relativeWeighting) pixelEstimatePass_ = std::make_unique<PixelEstimatePass>(ctx, spec, bindings_);
  generate_ = std::make_unique<GeneratePass>(ctx, spec, bindings_);
  prepare_ = std::make_unique<PreparePass>(ctx, spec, bindings_);
  intersect_ = std::make_unique<IntersectPass>(ctx, spec, bindings_);
  // Chosen by the device, not the method: the float-atomic variants only where statistics are
  // gathered and the context enabled VK_EXT_shader_atomic_float. The plain modules declare no
  // optional capability (the methods without statistics need none); they add the statistics with
  // compare-and-swap loops.
  casAtomics_ = useCms && !(s.floatAtomics && ctx.floatAtomics());
  floatAtomicVariants_ = useCms && !casAtomics_;
  shade_ = std::make_unique<ShadePass>(ctx, spec, bindings_, floatAtomicVariants_);
  shadow_ = std::make_unique<ShadowPass>(ctx, spec, bindings_, floatAtomicVariants_);
  accumulate_ = std::make_unique<AccumulatePass>(ctx, spec, bindings_);
  if (s.aovs) aov_ = std::make_unique<AovPass>(ctx, spec, bindings_);
  using Schedule = RenderSettings::Schedule;
  if (s.schedule == Schedule::Fused && !fusedScheduleRuns(s))
    throw Error("--schedule fused renders no --aov; use --schedule wavefront or auto");
  // Auto is the wavefront on GPUs. On a CPU device, where every dispatch of the wavefront ends in a
  // thread-pool barrier and a SIMD group runs all its lanes' code, the first submission runs the
  // wavefront and measures how many rays the paths trace (decideSchedule).
  autoSchedule_ = s.schedule == Schedule::Auto && fusedScheduleRuns(s) &&
                  ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  useFused_ = s.schedule == Schedule::Fused;
  // (Starting a new path in a lane whose path ended, path regeneration, did not speed the fused
  // kernel up: its one loop runs every stage's code, masked, at every bounce.)
  if (useFused_) buildFusedPass();

  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    buffer(shared::BINDING_QUEUE_STATE).fillZero(cmd);
    buffer(shared::BINDING_CELL_KEYS).fillZero(cmd);
    buffer(shared::BINDING_CELL_STATS).fillZero(cmd);
    buffer(shared::BINDING_CELL_SAMPLES).fillZero(cmd);
    buffer(shared::BINDING_CELL_SOLUTION).fillZero(cmd);   // no cell has a selection yet
    buffer(shared::BINDING_PIXEL_ESTIMATE).fillZero(cmd);
    // The pair table: no pair, no statistics, no coefficient yet; its keys then persist for the
    // whole render (shared/cms_pair_state.h).
    buffer(shared::BINDING_PAIR_KEYS).fillZero(cmd);
    buffer(shared::BINDING_PAIR_STATS).fillZero(cmd);
    buffer(shared::BINDING_PAIR_SAMPLES).fillZero(cmd);
    buffer(shared::BINDING_PAIR_ALPHA).fillZero(cmd);
    buffer(shared::BINDING_PAIR_COUNTERS).fillZero(cmd);
    buffer(shared::BINDING_PAIR_OCCUPIED).fillZero(cmd);   // no slot claimed
    recordClearFilm(cmd);
    // Solving the empty statistics gives every cell the default selection and no control variate.
    if (solver_) recordSolve(cmd, false);
  });

  fence_ = ctx.createFence();
  cmd_ = ctx.allocateCommandBuffer();
}

WavefrontRenderer::~WavefrontRenderer() {
  vkDeviceWaitIdle(ctx_.device());
  vkFreeCommandBuffers(ctx_.device(), ctx_.commandPool(), 1, &cmd_);
  vkDestroyFence(ctx_.device(), fence_, nullptr);
}

template <class Constants>
Constants WavefrontRenderer::vertexConstants(uint32_t paths, uint32_t pixelOffset, bool gathering) const {
  Constants c{};
  c.pathCount = paths;
  c.pixelOffset = pixelOffset;
  c.maxDepth = settings_.maxDepth;
  c.lightCount = lightCount_;
  c.clusterCount = clusterCount_;
  c.cellTableSize = cellTableSize_;
  c.gridOrigin = gridOrigin_;
  c.gridInvCellSize = gridInvCellSize_;
  c.gatherStatistics = gathering ? 1u : 0u;
  c.pairCapacity = pairCapacity_;
  c.emitterCount = emitterCount_;
  return c;
}

void WavefrontRenderer::recordSample(VkCommandBuffer cmd, uint32_t sampleIndex, uint32_t pixelOffset, uint32_t paths,
                                     bool gathering) {
  if (useFused_) {
    shared::FusedConstants fused = vertexConstants<shared::FusedConstants>(paths, pixelOffset, gathering);
    fused.sampleIndex = sampleIndex;
    fused.seed = settings_.seed;
    fused_->record(cmd, timer_, fused);
    accumulate_->record(cmd, timer_, shared::AccumulateConstants{paths, pixelOffset, sampleIndex});
    return;
  }
  generate_->record(cmd, timer_, shared::GenerateConstants{paths, pixelOffset, sampleIndex, settings_.seed});
  shared::VertexConstants vertex = vertexConstants<shared::VertexConstants>(paths, pixelOffset, gathering);
  for (uint32_t depth = 1; depth <= settings_.maxDepth; ++depth) {
    vertex.depth = depth;
    vertex.queueIn = (depth - 1) & 1u;
    prepare_->record(cmd, timer_, shared::PrepareConstants{shared::kPrepareRays, vertex.queueIn});
    intersect_->record(cmd, timer_, shared::IntersectConstants{paths, vertex.queueIn, queueForShade_ ? 1u : 0u});
    if (depth == 1 && aov_) aov_->record(cmd, timer_, shared::AovConstants{paths, pixelOffset, sampleIndex});
    vertex.shadeQueued = queueForShade_ ? 1u : 0u;
    if (queueForShade_) prepare_->record(cmd, timer_, shared::PrepareConstants{shared::kPrepareShade, vertex.queueIn});
    shade_->record(cmd, timer_, vertex, gathering);
    // The last depth only adds emission: no shadow rays; with the per-triangle control variate it
    // still queues the previous BSDF sample's pair terms for the shadow pass.
    if (depth < settings_.maxDepth || pairTechniques_) {
      prepare_->record(cmd, timer_, shared::PrepareConstants{shared::kPrepareShadows, vertex.queueIn});
      shadow_->record(cmd, timer_, vertex, gathering);
    }
  }
  accumulate_->record(cmd, timer_, shared::AccumulateConstants{paths, pixelOffset, sampleIndex});
}

shared::SolveParams WavefrontRenderer::solveParams() const {
  return solveParamsFor(settings_, cellTableSize_, clusterCount_);
}

WavefrontRenderer::CmsCellState WavefrontRenderer::cmsCellState() const {
  CmsCellState s;
  if (!solver_) return s;
  s.clusters = clusterCount_;
  s.keys = buffer(shared::BINDING_CELL_KEYS).downloadAll<uint64_t>();
  s.stats = buffer(shared::BINDING_CELL_STATS).downloadAll<float>();
  s.samples = buffer(shared::BINDING_CELL_SAMPLES).downloadAll<uint32_t>();
  s.solution = buffer(shared::BINDING_CELL_SOLUTION).downloadAll<float>();
  s.defaults = buffer(shared::BINDING_CLUSTER_DEFAULTS).downloadAll<float>();
  s.defaults.resize(clusterCount_);   // without the padding to whole texels
  s.params = solveParams();
  return s;
}

void WavefrontRenderer::recordSolve(VkCommandBuffer cmd, bool timed) {
  shared::SolveParams params = solveParams();
  if (sparseSolver_) {
    // The per-triangle control variate, in the CPU backend's order (host/cpu/cpu_cms_cells.cpp
    // solvePairs): 1. the sparse solve writes every cell's control variate; 2. the cluster solve
    // learns the selection and restarts cells, keeping that control variate; 3. the pairs of
    // restarted cells restart.
    const SparseSolveSettings sparse = sparseSolveSettings(params);
    sparseSolver_->record(cmd, sparse, timed ? &timer_ : nullptr);
    params.flags |= shared::kSolveKeepControlVariate;
    solver_->record(cmd, params);
    if (timed) timer_.mark(cmd, "solve");
    sparseSolver_->recordRestart(cmd, sparse, timed ? &timer_ : nullptr);
  } else {
    // The solve also restarts the statistics of cells whose selection changed (shared/cms_solve.h).
    solver_->record(cmd, params);
    if (timed) timer_.mark(cmd, "solve");
  }
  if (pixelEstimatePass_ && timed)   // (untimed: the set-up solve, before any film exists)
    pixelEstimatePass_->record(cmd, timer_, shared::PixelEstimateConstants{pixelCount_});
}

uint32_t WavefrontRenderer::solveMarks() const {
  // The sparse solve's stages ("sparse_solve.<stage>": 10) and its restart, the cluster solve, and
  // the pixel estimate: room kept for them, since a sample pass that solves marks more than one
  // that does not.
  return (sparseSolver_ ? 10u + 1u : 0u) + 1u + (pixelEstimatePass_ ? 1u : 0u);
}

SparseSolveSettings WavefrontRenderer::sparseSolveSettings(const shared::SolveParams& params) const {
  // The parameters of the CPU backend's double solve (host/cpu/cpu_cms_cells.cpp solvePairs).
  SparseSolveSettings s;
  s.cellCount = cellTableSize_;
  s.clusterCount = clusterCount_;
  s.pairCapacity = pairCapacity_;
  s.minSamples = params.minSamples;
  s.minTechniqueSamples = shared::kPairMinSamples;
  s.ridge = params.ridge;
  s.flags = shared::kSolveControlVariate;
  return s;
}

void WavefrontRenderer::renderSamples(uint32_t count) {
  while (count > 0) {
    vkResetCommandBuffer(cmd_, 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd_, &bi);
    timer_.begin(cmd_);
    // As many sample passes as the timer has room for, counted from what the passes recorded: each
    // marks one timestamp per dispatch, so a sample pass needs what the costliest one so far did.
    uint32_t n = 0;
    do {
      const uint32_t before = timer_.marked();
      const bool gathering = solver_ && schedule_.gathers(spp_ + n);
      for (uint32_t offset = 0; offset < pixelCount_; offset += pathCount_)
        recordSample(cmd_, spp_ + n, offset, std::min(pathCount_, pixelCount_ - offset), gathering);
      gatheringSamples_ += gathering;
      // Training iterations of doubling length (docs/estimator.md §7; cms/training_schedule.h).
      if (solver_ && schedule_.solvesAfter(spp_ + n + 1)) recordSolve(cmd_, true);
      marksPerSample_ = std::max(marksPerSample_, timer_.marked() - before);
      ++n;
    } while (n < count && timer_.room() >= marksPerSample_ + solveMarks());
    vkCheck(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    vkCheck(vkResetFences(ctx_.device(), 1, &fence_), "vkResetFences");
    vkCheck(vkQueueSubmit(ctx_.queue(), 1, &si, fence_), "vkQueueSubmit");
    vkCheck(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    timer_.collect();
    spp_ += n;
    count -= n;
    if (!probed_) decideFromFirstSubmission();
  }
}

void WavefrontRenderer::decideFromFirstSubmission() {
  probed_ = true;
  if (!queueForShade_ && !autoSchedule_) return;
  shared::QueueState q{};
  buffer(shared::BINDING_QUEUE_STATE).download(&q, sizeof(q));
  if (queueForShade_) decideShadeQueue(q);
  if (autoSchedule_) decideSchedule(q);
}

void WavefrontRenderer::decideSchedule(const shared::QueueState& q) {
  const double possible = double(spp_) * double(pixelCount_) * double(settings_.maxDepth);
  rayOccupancy_ = possible > 0.0 ? double(counterValue(q.extensionRays)) / possible : 0.0;
  useFused_ = rayOccupancy_ >= kFusedMinRayOccupancy;
  if (useFused_) buildFusedPass();
}

void WavefrontRenderer::buildFusedPass() {
  // Built only once a render runs it: on lavapipe compiling the fused kernel takes longer than
  // the rest of a small render's set-up (veach_mis, cms: 0.5-0.75 s).
  if (fused_) return;
  const auto start = std::chrono::steady_clock::now();
  fused_ = std::make_unique<FusedPass>(ctx_, spec_, bindings_, floatAtomicVariants_);
  // After the first submission it was built inside renderSamples: set-up the render's time counts.
  if (probed_) fusedBuildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void WavefrontRenderer::decideShadeQueue(const shared::QueueState& q) {
  const uint64_t traced = counterValue(q.extensionRays);
  const uint64_t hit = counterValue(q.shadedRays);
  // Queueing costs intersect about a tenth of its time (an atomic per SIMD group on a counter both
  // of lavapipe's worker threads share, and a store per ray) and saves shade the share of rays that
  // escaped, shade being a third to a half of a sample: below some 15 % escaped it loses
  // (benchmarks/README.md, "What a pass costs on lavapipe").
  if (traced == 0 || double(traced - std::min(hit, traced)) < kShadeQueueMinEscaped * double(traced)) queueForShade_ = false;
}

void WavefrontRenderer::restart(const shared::CameraGpu& camera) {
  vkCheck(vkDeviceWaitIdle(ctx_.device()), "vkDeviceWaitIdle");
  shared::CameraGpu c = camera;
  c.width = settings_.width;
  c.height = settings_.height;
  scene_.camera.upload(&c, sizeof(c));
  ctx_.submitAndWait([&](VkCommandBuffer cmd) { recordClearFilm(cmd); });
  // The training schedule starts over: the cells keep what they learned, and the next solves
  // refine it with statistics weighted by the new image's pixel estimate.
  spp_ = 0;
}

void WavefrontRenderer::recordClearFilm(VkCommandBuffer cmd) {
  buffer(shared::BINDING_FILM).fillZero(cmd);
  buffer(shared::BINDING_AOV).fillZero(cmd);
  vkCmdFillBuffer(cmd, buffer(shared::BINDING_FIRST_CELL).handle(), 0, VK_WHOLE_SIZE, shared::kNoCell);   // no pixel has a hit yet
  computeBarrier(cmd);
}

Image WavefrontRenderer::readImage(Image* standardError) const {
  std::vector<glm::vec3> film(size_t(pixelCount_) * 2);
  buffer(shared::BINDING_FILM).download(film.data(), film.size() * sizeof(glm::vec3));
  Image mean;
  mean.width = int(settings_.width);
  mean.height = int(settings_.height);
  mean.rgb.assign(size_t(pixelCount_) * 3, 0.0f);
  if (standardError) *standardError = mean;
  if (spp_ == 0) return mean;
  for (size_t p = 0; p < pixelCount_; ++p)
    for (int c = 0; c < 3; ++c) {
      mean.rgb[3 * p + c] = film[2 * p][c];
      if (standardError) standardError->rgb[3 * p + c] = shared::standardErrorOfMean(film[2 * p + 1][c], float(spp_));
    }
  return mean;
}

AovImages WavefrontRenderer::readAovs() const {
  if (!settings_.aovs) return {};
  std::vector<glm::vec3> aov(size_t(pixelCount_) * shared::kAovStride);
  buffer(shared::BINDING_AOV).download(aov.data(), aov.size() * sizeof(glm::vec3));
  return aovImagesFrom(aov, settings_.width, settings_.height);
}

std::string WavefrontRenderer::deviceName() const { return ctx_.deviceName(); }

RenderCounters WavefrontRenderer::counters() const {
  shared::QueueState q{};
  buffer(shared::BINDING_QUEUE_STATE).download(&q, sizeof(q));
  RenderCounters c;
  c.nonFiniteSamples = q.nonFinite;
  c.extensionRays = counterValue(q.extensionRays);
  c.shadowRays = counterValue(q.shadowRays);
  c.schedule = useFused_ ? "fused" : "wavefront";
  if (!useFused_) c.shadeQueue = queueForShade_ ? "hits" : "rays";
  if (autoSchedule_) c.autoRayOccupancy = rayOccupancy_;
  if (solver_) {
    c.verticesWithoutCell = q.verticesWithoutCell;
    c.cellTableSize = cellTableSize_;
    c.statisticsAtomics = casAtomics_ ? "cas" : "float";
    c.gatheringSamples = gatheringSamples_;
    for (uint64_t key : buffer(shared::BINDING_CELL_KEYS).downloadAll<uint64_t>()) c.cellsUsed += key != 0;
    if (settings_.cms.controlVariate) reportPairs(c);
  }
  return c;
}

void WavefrontRenderer::reportPairs(RenderCounters& c) const {
  // The CPU backend's fields (host/cpu/cpu_cms_cells.cpp reportPairs).
  c.cvTechniques = pairTechniques_ ? "triangle" : "cluster";
  c.techniques = pairTechniques_ ? techniqueCount_ : clusterCount_;
  c.techniquesMerged = techniquesMerged_;
  if (!pairTechniques_) return;
  c.pairTableCapacity = pairCapacity_;
  uint32_t used = 0;   // the occupied list's count (shared/cms_pair_state.h)
  buffer(shared::BINDING_PAIR_OCCUPIED).download(&used, sizeof(used), shared::kPairOccupiedCount * sizeof(uint32_t));
  c.pairsUsed = used;
  const std::vector<uint32_t> counters = buffer(shared::BINDING_PAIR_COUNTERS).downloadAll<uint32_t>();
  c.pairSamples = counters[shared::kPairCounterPairSamples];
  c.pairRefusedSamples = counters[shared::kPairCounterRefusedSamples];
  c.pairRemainderSamples = counters[shared::kPairCounterRemainderSamples];
  // Keys, statistics and counts (shared/cms_pair_layout.h), alpha, the occupied list, and the
  // sparse solve's own buffers.
  c.pairBufferBytes = uint64_t(pairCapacity_) * (shared::kPairBytesPerSlot + 4u * shared::kPairAlphaStride) +
                      4u * (uint64_t(pairCapacity_) + shared::kPairOccupiedFirst) + sparseSolver_->scratchBytes();
}

}  // namespace mixtrace
