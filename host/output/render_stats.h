#pragma once
// What a render reports about itself: written as the --stats JSON and summarised on stderr.
#include <cstdint>
#include <map>
#include <string>

namespace mixtrace {

struct RenderStats {
  std::string scene, method, backend, device, features;
  std::string estimator;   // what ran: the method, or pt-power where cms reduces to it (cms/cms_setup.h)
  uint32_t width = 0, height = 0, maxDepth = 0, seed = 0;
  uint32_t spp = 0;
  uint32_t targetSpp = 0;       // what was asked for; 0 when open-ended (--time)
  std::string interruptedBy;    // "SIGINT"/"SIGTERM" when stopped early, with spp < targetSpp
  double renderSeconds = 0.0;   // sample passes only, excluding set-up
  double setupSeconds = 0.0;    // loading, BVH, upload, pipeline creation
  double bvhBuildSeconds = 0.0;
  uint64_t triangles = 0, lights = 0, bvhNodes = 0;
  uint64_t extensionRays = 0, shadowRays = 0;
  uint64_t nonFiniteSamples = 0;  // caught and dropped, never written to the image
  uint64_t cmsCellsUsed = 0, cmsCellTableSize = 0, cmsVerticesWithoutCell = 0;
  uint32_t cmsClusters = 0;
  uint32_t cmsGridCells = 0;      // the grid's cells along the longest axis (--cells)
  bool cmsGridCellsAuto = false;  // chosen by --cells auto (cms/grid_resolution.h)
  uint32_t cmsGatheringSpp = 0;   // sample passes that gathered statistics (the training schedule)
  std::string cmsAtomics;   // how the statistics are added: "float" or "cas" (Vulkan)
  std::string schedule;     // Vulkan: "wavefront" or "fused"
  std::string shadeQueue;   // Vulkan wavefront: "hits" or "rays" (RenderCounters::shadeQueue)
  double autoRayOccupancy = -1.0;   // RenderCounters::autoRayOccupancy (-1: not chosen by it)
  // The control variate's techniques (cv, cms): "triangle" or "cluster", how many, whether
  // triangles were merged to fit the budget, and with "triangle" the (cell, technique) pair table.
  std::string cmsCvTechniques;
  uint64_t cmsTechniques = 0;
  bool cmsTechniquesMerged = false;
  uint64_t cmsPairTableCapacity = 0, cmsPairsUsed = 0, cmsPairSamples = 0, cmsPairRefusedSamples = 0,
           cmsPairRemainderSamples = 0;
  uint64_t cmsPairBufferBytes = 0;
  uint32_t validationErrors = 0;
  std::map<std::string, double> passMs;  // GPU time per pass (Vulkan timestamp queries)

  double samplesPerSecond() const;
  double raysPerSecond() const;
};

// Written atomically (output/atomic_file.h).
void writeStatsJson(const std::string& path, const RenderStats& stats);

}  // namespace mixtrace
