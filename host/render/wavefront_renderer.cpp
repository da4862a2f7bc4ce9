#include "render/wavefront_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "cms/cell_grid.h"
#include "shared/bindings.h"
#include "shared/film.h"
#include "util/error.h"
#include "vulkan/check.h"
#include "vulkan/context.h"

namespace mixtrace {
namespace {


uint32_t groupsFor(uint32_t n) { return (n + shared::kWorkgroupSize - 1) / shared::kWorkgroupSize; }

}  // namespace

WavefrontRenderer::WavefrontRenderer(VulkanContext& ctx, const PreparedScene& scene, const MethodLights& lights,
                                     const RenderSettings& s)
    : ctx_(ctx),
      settings_(s),
      lightCount_(uint32_t(scene.lights.lights.size())),
      pixelCount_(s.width * s.height),
      pathCount_(std::min(s.width * s.height, s.maxPathsPerChunk)),
      scene_(ctx, scene, makeCamera(scene.scene, s.width, s.height)),
      lightSelection_(makeBuffer(ctx, lights.selection, "light selection")),
      set_(ctx, BINDING_COUNT, sizeof(shared::PassConstants)),
      rayOrigin_(ctx, size_t(pathCount_) * sizeof(glm::vec3), "path state (ray origins)"),
      rayDirection_(ctx, size_t(pathCount_) * sizeof(glm::vec3), "path state (ray directions)"),
      throughput_(ctx, size_t(pathCount_) * sizeof(glm::vec3), "path state (throughput)"),
      radiance_(ctx, size_t(pathCount_) * sizeof(glm::vec3), "path state (radiance)"),
      rng_(ctx, size_t(pathCount_) * sizeof(uint32_t), "path state (random numbers)"),
      misPdf_(ctx, size_t(pathCount_) * sizeof(float), "path state (MIS pdfs)"),
      hits_(ctx, size_t(pathCount_) * sizeof(shared::HitRecord), "path state (hits)"),
      rayQueue_(ctx, size_t(pathCount_) * 2 * sizeof(uint32_t), "ray queues"),
      shadowQueue_(ctx, size_t(pathCount_) * sizeof(shared::ShadowRay), "shadow-ray queue"),
      queueState_(ctx, sizeof(shared::QueueState), "queue counters", true),
      film_(ctx, size_t(pixelCount_) * 2 * sizeof(glm::vec3), "film (" + std::to_string(s.width) + "x" + std::to_string(s.height) + ")", true),
      timer_(ctx, 4096) {
  if (s.maxDepth < 1) throw Error("--max-depth must be at least 1");
  if (lights.selection.size() != lightCount_) throw Error("internal: a light selection table of another scene");
  const CmsScene* cms = s.cms.clusters ? &lights.cms : nullptr;
  setUpTraining(s);
  scene_.bindTo(set_);
  set_.bind(BINDING_LIGHT_SELECTION, lightSelection_);
  // CMS buffers (placeholders of one element for the other methods, so every binding is valid).
  const bool useCms = s.cms.clusters && cms && !cms->clusters.clusters.empty();
  clusterCount_ = useCms ? uint32_t(cms->clusters.clusters.size()) : 1;
  const CellGridSetup grid = makeCellGrid(scene.scene.bounds, s.cells, clusterCount_);
  cellTableSize_ = useCms ? grid.tableSize : 1;
  const size_t cvPaths = useCms ? pathCount_ : 1;
  cellKeys_ = Buffer(ctx, size_t(cellTableSize_) * sizeof(uint64_t), "CMS cell table");
  cellStats_ = Buffer(ctx, size_t(cellTableSize_) * shared::cellStatsStride(clusterCount_) * sizeof(float), "CMS cell statistics");
  cellSamples_ = Buffer(ctx, size_t(cellTableSize_) * sizeof(uint32_t), "CMS cell sample counts");
  cellSolution_ = Buffer(ctx, size_t(cellTableSize_) * shared::cellSolutionStride(clusterCount_) * sizeof(float), "CMS cell solutions");
  clusterDefaults_ = makeBuffer(ctx, useCms ? cms->clusters.defaultSelection : std::vector<float>{1.0f}, "cluster defaults");
  clusters_ = makeBuffer(ctx, useCms ? cms->clusters.clusters : std::vector<shared::ClusterGpu>(1), "clusters");
  clusterLights_ = makeBuffer(ctx, useCms ? cms->clusterLights : std::vector<shared::ClusterLightGpu>(1), "cluster lights");
  cvState_ = Buffer(ctx, cvPaths * sizeof(shared::CvPathState), "path state (CMS)");
  pixelEstimate_ = Buffer(ctx, size_t(useCms ? pixelCount_ : 1) * sizeof(glm::vec3), "CMS pixel estimate");
  firstCell_ = Buffer(ctx, size_t(useCms ? pixelCount_ : 1) * sizeof(uint32_t), "CMS first-hit cells");
  displayPlaceholder_ = Buffer(ctx, sizeof(uint32_t), "display placeholder");
  if (useCms) {
    gridOrigin_ = grid.origin;
    gridInvCellSize_ = grid.invCellSize;
  }
  set_.bind(BINDING_CELL_KEYS, cellKeys_);
  set_.bind(BINDING_CELL_STATS, cellStats_);
  set_.bind(BINDING_CELL_SAMPLES, cellSamples_);
  set_.bind(BINDING_CELL_SOLUTION, cellSolution_);
  set_.bind(BINDING_CLUSTER_DEFAULTS, clusterDefaults_);
  set_.bind(BINDING_CLUSTERS, clusters_);
  set_.bind(BINDING_CLUSTER_LIGHTS, clusterLights_);
  set_.bind(BINDING_CV_STATE, cvState_);
  set_.bind(BINDING_PIXEL_ESTIMATE, pixelEstimate_);
  set_.bind(BINDING_FIRST_CELL, firstCell_);
  set_.bind(BINDING_DISPLAY, displayPlaceholder_);
  set_.bind(BINDING_RAY_ORIGIN, rayOrigin_);
  set_.bind(BINDING_RAY_DIRECTION, rayDirection_);
  set_.bind(BINDING_THROUGHPUT, throughput_);
  set_.bind(BINDING_RADIANCE, radiance_);
  set_.bind(BINDING_RNG, rng_);
  set_.bind(BINDING_MIS_PDF, misPdf_);
  set_.bind(BINDING_HITS, hits_);
  set_.bind(BINDING_RAY_QUEUE, rayQueue_);
  set_.bind(BINDING_SHADOW_QUEUE, shadowQueue_);
  set_.bind(BINDING_QUEUE_STATE, queueState_);
  set_.bind(BINDING_FILM, film_);

  spec_ = (s.generalPipelines ? FeatureSet::general() : scene.features).specialization();
  std::vector<uint32_t>& spec = spec_;
  spec[SPEC_CMS_SELECTION] = useCms;
  spec[SPEC_CMS_CONTROL_VARIATE] = useCms && s.cms.controlVariate;
  spec[SPEC_CMS_RELATIVE_WEIGHT] = useCms && s.relativeWeighting;
  if (useCms) solver_ = std::make_unique<CellSolver>(ctx, set_);
  if (useCms && s.relativeWeighting)
    pixelEstimatePass_ = std::make_unique<ComputePipeline>(ctx, "pixel_estimate", set_.pipelineLayout(), spec);
  VkPipelineLayout layout = set_.pipelineLayout();
  generate_ = std::make_unique<ComputePipeline>(ctx, "generate", layout, spec);
  prepare_ = std::make_unique<ComputePipeline>(ctx, "prepare", layout, spec);
  intersect_ = std::make_unique<ComputePipeline>(ctx, "intersect", layout, spec);
  // Chosen by the device, not the method: the float-atomic variants only where statistics are
  // gathered and the context enabled VK_EXT_shader_atomic_float. The plain modules declare no
  // optional capability (the methods without statistics need none); they add the statistics with
  // compare-and-swap loops.
  casAtomics_ = useCms && !(s.floatAtomics && ctx.floatAtomics());
  const bool floatAtomicVariants = useCms && !casAtomics_;
  shade_ = std::make_unique<ComputePipeline>(ctx, floatAtomicVariants ? "shade_float_atomics" : "shade", layout, spec,
                                             "shade");
  shadow_ = std::make_unique<ComputePipeline>(ctx, floatAtomicVariants ? "shadow_float_atomics" : "shadow", layout,
                                              spec, "shadow");
  accumulate_ = std::make_unique<ComputePipeline>(ctx, "accumulate", layout, spec);

  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    queueState_.fillZero(cmd);
    cellKeys_.fillZero(cmd);
    cellStats_.fillZero(cmd);
    cellSamples_.fillZero(cmd);
    cellSolution_.fillZero(cmd);   // no cell has a selection yet
    pixelEstimate_.fillZero(cmd);
    recordClearFilm(cmd);
    // Solving the empty statistics gives every cell the default selection and no control variate.
    if (solver_) {
      VkDescriptorSet set = set_.set();
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, set_.pipelineLayout(), 0, 1, &set, 0, nullptr);
      recordSolve(cmd, false);
    }
  });

  fence_ = ctx.createFence();
  cmd_ = ctx.allocateCommandBuffer();
}

WavefrontRenderer::~WavefrontRenderer() {
  vkDeviceWaitIdle(ctx_.device());
  vkFreeCommandBuffers(ctx_.device(), ctx_.commandPool(), 1, &cmd_);
  vkDestroyFence(ctx_.device(), fence_, nullptr);
}

void WavefrontRenderer::dispatch(VkCommandBuffer cmd, const ComputePipeline& p, const shared::PassConstants& pc,
                                 uint32_t groups) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  vkCmdPushConstants(cmd, set_.pipelineLayout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, groups, 1, 1);
  computeBarrier(cmd);
  timer_.mark(cmd, p.name().c_str());
}

void WavefrontRenderer::dispatchIndirect(VkCommandBuffer cmd, const ComputePipeline& p,
                                         const shared::PassConstants& pc, VkDeviceSize offset, const char* label) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  vkCmdPushConstants(cmd, set_.pipelineLayout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdDispatchIndirect(cmd, queueState_.handle(), offset);
  computeBarrier(cmd);
  timer_.mark(cmd, label ? label : p.name().c_str());
}

void WavefrontRenderer::recordSample(VkCommandBuffer cmd, uint32_t sampleIndex, uint32_t pixelOffset, uint32_t paths,
                                     bool gathering) {
  shared::PassConstants pc{};
  pc.pathCount = paths;
  pc.pixelOffset = pixelOffset;
  pc.sampleIndex = sampleIndex;
  pc.seed = settings_.seed;
  pc.maxDepth = settings_.maxDepth;
  pc.lightCount = lightCount_;
  pc.clusterCount = clusterCount_;
  pc.cellTableSize = cellTableSize_;
  pc.gridOrigin = gridOrigin_;
  pc.gridInvCellSize = gridInvCellSize_;
  pc.gatherStatistics = gathering ? 1u : 0u;

  dispatch(cmd, *generate_, pc, groupsFor(paths));
  for (uint32_t depth = 1; depth <= settings_.maxDepth; ++depth) {
    pc.depth = depth;
    pc.queueIn = (depth - 1) & 1u;
    pc.mode = shared::kPrepareRays;
    dispatch(cmd, *prepare_, pc, 1);
    dispatchIndirect(cmd, *intersect_, pc, offsetof(shared::QueueState, rayArgs));
    dispatchIndirect(cmd, *shade_, pc, offsetof(shared::QueueState, rayArgs), gathering ? "shade+statistics" : nullptr);
    if (depth < settings_.maxDepth) {   // the last depth only adds emission: no shadow rays
      pc.mode = shared::kPrepareShadows;
      dispatch(cmd, *prepare_, pc, 1);
      dispatchIndirect(cmd, *shadow_, pc, offsetof(shared::QueueState, shadowArgs),
                       gathering ? "shadow+statistics" : nullptr);
    }
  }
  dispatch(cmd, *accumulate_, pc, groupsFor(paths));
}

shared::SolveParams WavefrontRenderer::solveParams() const {
  return solveParamsFor(settings_, cellTableSize_, clusterCount_);
}

WavefrontRenderer::CmsCellState WavefrontRenderer::cmsCellState() const {
  CmsCellState s;
  if (!solver_) return s;
  s.clusters = clusterCount_;
  s.keys = cellKeys_.downloadAll<uint64_t>();
  s.stats = cellStats_.downloadAll<float>();
  s.samples = cellSamples_.downloadAll<uint32_t>();
  s.solution = cellSolution_.downloadAll<float>();
  s.defaults = clusterDefaults_.downloadAll<float>();
  s.params = solveParams();
  return s;
}

void WavefrontRenderer::recordSolve(VkCommandBuffer cmd, bool timed) {
  const shared::SolveParams params = solveParams();
  // The solve also restarts the statistics of cells whose selection changed (shared/cms_solve.h).
  solver_->record(cmd, params);
  if (timed) timer_.mark(cmd, "solve");
  if (pixelEstimatePass_ && timed) {   // (untimed: the set-up solve, before any film exists)
    shared::PassConstants pc{};
    pc.pathCount = pixelCount_;
    dispatch(cmd, *pixelEstimatePass_, pc, groupsFor(pixelCount_));
  }
}

void WavefrontRenderer::renderSamples(uint32_t count) {
  const uint32_t passesPerSample = 4 + 3 * settings_.maxDepth + 2 * (settings_.maxDepth - 1);  // + solve, estimate
  const uint32_t chunks = (pixelCount_ + pathCount_ - 1) / pathCount_;
  const uint32_t perSubmit = std::max(1u, (timer_.capacity() - 2) / (passesPerSample * chunks));
  while (count > 0) {
    uint32_t n = std::min(count, perSubmit);
    vkResetCommandBuffer(cmd_, 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd_, &bi);
    timer_.begin(cmd_);
    VkDescriptorSet set = set_.set();
    vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, set_.pipelineLayout(), 0, 1, &set, 0, nullptr);
    for (uint32_t s = 0; s < n; ++s) {
      const bool gathering = solver_ && schedule_.gathers(spp_ + s);
      for (uint32_t offset = 0; offset < pixelCount_; offset += pathCount_)
        recordSample(cmd_, spp_ + s, offset, std::min(pathCount_, pixelCount_ - offset), gathering);
      gatheringSamples_ += gathering;
      // Training iterations of doubling length (docs/estimator.md §7; cms/training_schedule.h).
      if (solver_ && schedule_.solvesAfter(spp_ + s + 1)) recordSolve(cmd_, true);
    }
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
  }
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
  film_.fillZero(cmd);
  vkCmdFillBuffer(cmd, firstCell_.handle(), 0, VK_WHOLE_SIZE, shared::kNoCell);   // no pixel has a hit yet
  computeBarrier(cmd);
}

Image WavefrontRenderer::readImage(Image* standardError) const {
  std::vector<glm::vec3> film(size_t(pixelCount_) * 2);
  film_.download(film.data(), film.size() * sizeof(glm::vec3));
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

std::string WavefrontRenderer::deviceName() const { return ctx_.deviceName(); }

RenderCounters WavefrontRenderer::counters() const {
  shared::QueueState q{};
  queueState_.download(&q, sizeof(q));
  RenderCounters c;
  c.nonFiniteSamples = q.nonFinite;
  c.extensionRays = uint64_t(q.extensionRays[0]) | (uint64_t(q.extensionRays[1]) << 32);
  c.shadowRays = uint64_t(q.shadowRays[0]) | (uint64_t(q.shadowRays[1]) << 32);
  if (solver_) {
    c.verticesWithoutCell = q.verticesWithoutCell;
    c.cellTableSize = cellTableSize_;
    c.statisticsAtomics = casAtomics_ ? "cas" : "float";
    c.gatheringSamples = gatheringSamples_;
    for (uint64_t key : cellKeys_.downloadAll<uint64_t>()) c.cellsUsed += key != 0;
  }
  return c;
}

}  // namespace mixtrace
