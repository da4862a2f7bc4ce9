#include "app/render_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "session/default_scene.h"
#include "session/method_setup.h"
#include "session/output_plan.h"
#include "session/sample_loop.h"
#include "session/scene_camera.h"
#include "app/stop_on_signal.h"
#include "output/render_output.h"
#include "output/render_stats.h"
#include "cms/cms_setup.h"
#include "cpu/cpu_renderer.h"
#include "wavefront/wavefront_renderer.h"
#include "scene/prepared_scene.h"
#include "util/error.h"
#include "util/log.h"
#include "util/progress.h"
#include "util/timing.h"
#include "vulkan/context.h"

namespace mixtrace {
namespace {

// "1 light", "3 lights".
std::string counted(size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// An image with no pixel above zero is almost never what was meant; say why it may be so.
void warnIfBlack(const Image& image, const PreparedScene& prepared) {
  for (float v : image.rgb)
    if (v > 0.0f) return;
  const size_t lights = prepared.lights.lights.size();
  if (lights == 0) {
    warn("the image is entirely black: the scene has no lights");
  } else if (!prepared.scene.camera.fromFile) {
    warn("the image is entirely black although the scene has " + counted(lights, "light") +
         "; the default camera looks at the scene from outside its bounds, where a closed room shows only "
         "its outside: set a camera with --look-from X,Y,Z --look-at X,Y,Z");
  } else {
    warn("the image is entirely black although the scene has " + counted(lights, "light") +
         " (is the camera inside a closed object, or facing away from the scene?)");
  }
}

// The backend the options name, over the prepared scene and the method's light tables.
std::unique_ptr<Renderer> makeRenderer(const RenderOptions& o, VulkanContext* ctx, const PreparedScene& prepared,
                                       const MethodSetup& setup) {
  if (o.backend == "cpu") return std::make_unique<CpuRenderer>(prepared, setup.lights, setup.settings);
  return std::make_unique<WavefrontRenderer>(*ctx, prepared, setup.lights, setup.settings);
}

struct RenderRun {
  double seconds = 0.0;
  bool timed = false;
  uint32_t targetSpp = 0;
};

// The sample passes, in batches (session/sample_loop.h), with the progress line, until the target,
// the time budget or a stop request (Ctrl-C).
RenderRun renderUntilDone(const RenderOptions& o, Renderer& renderer, const StopOnSignal& stop) {
  SampleLoop loop(renderer, sampleTargetFor(o));
  RenderRun run;
  run.timed = loop.timed();
  run.targetSpp = loop.targetSpp();
  const double pixels = double(o.width) * o.height;
  Progress progress(!o.quiet);
  auto renderStart = Clock::now();
  while (loop.step()) {
    if (stop.requested() || loop.outOfTime()) break;
    const uint32_t spp = renderer.samplesPerPixel();
    progress.update(loop.fraction(), std::to_string(spp) + (run.timed ? "" : "/" + std::to_string(run.targetSpp)) +
                                         " spp, " + formatRate(spp * pixels / loop.seconds()) + " samples/s");
  }
  run.seconds = secondsSince(renderStart) - renderer.setupSecondsDuringRender();
  progress.finish();
  return run;
}

// What --stats writes: the render's settings, sizes, counters and timings.
RenderStats collectStats(const RenderOptions& o, const PreparedScene& prepared, const MethodSetup& setup,
                         const Renderer& renderer, const RenderRun& run, const RenderCounters& counters) {
  RenderStats stats;
  stats.scene = prepared.scene.name;
  stats.method = o.method;
  stats.backend = o.backend;
  stats.device = renderer.deviceName();
  stats.features = (o.generalPipelines ? FeatureSet::general() : prepared.features).describe();
  stats.width = uint32_t(o.width);
  stats.height = uint32_t(o.height);
  stats.maxDepth = uint32_t(o.maxDepth);
  stats.seed = o.seed;
  stats.spp = renderer.samplesPerPixel();
  stats.targetSpp = run.timed && o.spp <= 0 ? 0 : run.targetSpp;
  stats.renderSeconds = run.seconds;
  stats.bvhBuildSeconds = prepared.bvh.buildSeconds;
  stats.triangles = prepared.scene.triangles.size();
  stats.bvhNodes = prepared.bvh.nodes.size();
  stats.lights = prepared.lights.lights.size();
  stats.extensionRays = counters.extensionRays;
  stats.shadowRays = counters.shadowRays;
  stats.nonFiniteSamples = counters.nonFiniteSamples;
  stats.cmsCellsUsed = counters.cellsUsed;
  stats.cmsCellTableSize = counters.cellTableSize;
  stats.cmsVerticesWithoutCell = counters.verticesWithoutCell;
  stats.cmsClusters = uint32_t(setup.lights.cms.clusters.clusters.size());
  stats.cmsGridCells = setup.settings.cells;
  stats.cmsGridCellsAuto = setup.cellsChosen;
  stats.cmsAtomics = counters.statisticsAtomics;
  stats.schedule = counters.schedule;
  stats.shadeQueue = counters.shadeQueue;
  stats.autoRayOccupancy = counters.autoRayOccupancy;
  stats.estimator = setup.estimator;
  stats.cmsGatheringSpp = counters.gatheringSamples;
  stats.cmsCvTechniques = counters.cvTechniques;
  stats.cmsTechniques = counters.techniques;
  stats.cmsTechniquesMerged = counters.techniquesMerged;
  stats.cmsPairTableCapacity = counters.pairTableCapacity;
  stats.cmsPairsUsed = counters.pairsUsed;
  stats.cmsPairSamples = counters.pairSamples;
  stats.cmsPairRefusedSamples = counters.pairRefusedSamples;
  stats.cmsPairRemainderSamples = counters.pairRemainderSamples;
  stats.cmsPairBufferBytes = counters.pairBufferBytes;
  stats.passMs = renderer.passTimesMs();
  return stats;
}

}  // namespace

int runRender(const RenderOptions& given) {
  RenderOptions o = given;   // the film's shape may still come from the file (applyFileAspectRatio)
  setQuiet(o.quiet);
  const std::string scenePath = o.scene.empty() ? defaultScenePath() : o.scene;
  // Before anything slow: a typo in an output's name must not cost a render.
  const OutputPlan outputs = planRenderOutputs(o, scenePath);

  auto setupStart = Clock::now();
  // The device next, before the scene: a wrong --device must not cost loading a large scene.
  std::unique_ptr<VulkanContext> ctx;
  if (o.backend != "cpu") ctx = std::make_unique<VulkanContext>(ContextOptions{o.device, o.validation});
  Scene scene = loadSceneForRendering(scenePath, o);
  applyFileAspectRatio(o, scene);
  const PreparedScene prepared = prepareScene(std::move(scene));
  const MethodSetup setup = setUpMethod(prepared, o, o.method);
  const std::unique_ptr<Renderer> renderer = makeRenderer(o, ctx.get(), prepared, setup);
  const double setupSeconds = secondsSince(setupStart);
  // From here on, Ctrl-C keeps what has been rendered (app/stop_on_signal.h).
  StopOnSignal stop(!o.quiet);
  info("scene " + prepared.scene.name + ": " + counted(prepared.scene.triangles.size(), "triangle") + ", " +
       counted(prepared.lights.lights.size(), "light") + "; device " + renderer->deviceName() + "; " +
       prepared.features.describe());

  const RenderRun run = renderUntilDone(o, *renderer, stop);
  // Decided here: a signal during the writes below is only a request to stop early, and the
  // render has already ended.
  const std::string stoppedBy = stop.signalName();
  const int stopExitCode = stop.exitCode();

  Image standardError;   // --variance: the standard error of each pixel's mean (shared/film.h)
  Image image = renderer->readImage(o.variance ? &standardError : nullptr);
  const RenderCounters counters = renderer->counters();
  RenderStats stats = collectStats(o, prepared, setup, *renderer, run, counters);
  stats.interruptedBy = stoppedBy;
  stats.setupSeconds = setupSeconds + renderer->setupSecondsDuringRender();
  stats.validationErrors = ctx ? ctx->validationErrors() : 0;
  if (counters.verticesWithoutCell > 0)
    warn("the CMS cell table (" + std::to_string(counters.cellTableSize) + " cells) was full for " +
         std::to_string(counters.verticesWithoutCell) +
         " vertices; they used no control variate (still unbiased); a smaller --cells fits");
  if (!stoppedBy.empty())
    warn("stopped by " + stats.interruptedBy + " after " + std::to_string(stats.spp) +
         (stats.targetSpp > 0 ? " of " + std::to_string(stats.targetSpp) : std::string()) +
         " spp; writing what has been rendered");

  RenderOutputInfo written{o.method, setup.estimator, prepared.scene.name, int(stats.spp), int(stats.targetSpp),
                           run.seconds, stats.interruptedBy};
  const AovImages aovs = renderer->readAovs();
  std::vector<ExrLayer> layers;
  for (const std::string& name : outputs.aovs) {
    if (name == "albedo") layers.push_back({{"albedo.R", "albedo.G", "albedo.B"}, &aovs.albedo});
    if (name == "normal") layers.push_back({{"normal.X", "normal.Y", "normal.Z"}, &aovs.normal});
    if (name == "depth") layers.push_back({{"depth.Z"}, &aovs.depth});
  }
  writeRenderOutput(outputs.image, image, o.variance ? &standardError : nullptr, written, o.png, layers);
  if (!outputs.stats.empty()) writeStatsJson(outputs.stats, stats);

  info("wrote " + outputs.image + ": " + std::to_string(stats.spp) + " spp in " + std::to_string(run.seconds) +
       " s, " + formatRate(stats.samplesPerSecond()) + " samples/s, " + formatRate(stats.raysPerSecond()) + " rays/s");
  warnIfBlack(image, prepared);
  if (stats.nonFiniteSamples > 0)
    warn(std::to_string(stats.nonFiniteSamples) + " non-finite samples were dropped from the image");
  if (stats.validationErrors > 0) {
    std::fprintf(stderr, "mixtrace: error: the Vulkan validation layer reported %u error(s)\n", stats.validationErrors);
    return 1;
  }
  return stopExitCode;
}

}  // namespace mixtrace
