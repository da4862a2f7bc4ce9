#include "output/render_stats.h"

#include <nlohmann/json.hpp>

#include "output/atomic_file.h"

namespace mixtrace {

double RenderStats::samplesPerSecond() const {
  return renderSeconds > 0.0 ? double(spp) * width * height / renderSeconds : 0.0;
}

double RenderStats::raysPerSecond() const {
  return renderSeconds > 0.0 ? double(extensionRays + shadowRays) / renderSeconds : 0.0;
}

void writeStatsJson(const std::string& path, const RenderStats& s) {
  nlohmann::json j;
  j["scene"] = s.scene;
  j["method"] = s.method;
  j["estimator"] = s.estimator.empty() ? s.method : s.estimator;
  j["backend"] = s.backend;
  j["device"] = s.device;
  j["features"] = s.features;
  j["width"] = s.width;
  j["height"] = s.height;
  j["max_depth"] = s.maxDepth;
  j["seed"] = s.seed;
  j["spp"] = s.spp;
  if (s.targetSpp > 0) j["target_spp"] = s.targetSpp;
  j["interrupted"] = !s.interruptedBy.empty();
  if (!s.interruptedBy.empty()) j["interrupted_by"] = s.interruptedBy;
  j["render_seconds"] = s.renderSeconds;
  j["setup_seconds"] = s.setupSeconds;
  j["samples_per_second"] = s.samplesPerSecond();
  j["rays_per_second"] = s.raysPerSecond();
  j["extension_rays"] = s.extensionRays;
  j["shadow_rays"] = s.shadowRays;
  j["bvh_build_seconds"] = s.bvhBuildSeconds;
  j["triangles"] = s.triangles;
  j["bvh_nodes"] = s.bvhNodes;
  j["lights"] = s.lights;
  j["non_finite_samples"] = s.nonFiniteSamples;
  if (!s.schedule.empty()) j["schedule"] = s.schedule;
  if (!s.shadeQueue.empty()) j["shade_queue"] = s.shadeQueue;
  if (s.autoRayOccupancy >= 0.0) j["schedule_ray_occupancy"] = s.autoRayOccupancy;
  if (s.cmsCellTableSize > 0) {
    j["cms_clusters"] = s.cmsClusters;
    j["cms_gathering_spp"] = s.cmsGatheringSpp;
    j["cms_grid_cells"] = s.cmsGridCells;
    j["cms_grid_cells_auto"] = s.cmsGridCellsAuto;
    j["cms_cells_used"] = s.cmsCellsUsed;
    j["cms_cell_table_size"] = s.cmsCellTableSize;
    j["cms_vertices_without_cell"] = s.cmsVerticesWithoutCell;
    if (!s.cmsAtomics.empty()) j["cms_statistics_atomics"] = s.cmsAtomics;
    if (!s.cmsCvTechniques.empty()) {
      j["cms_cv_techniques"] = s.cmsCvTechniques;
      j["cms_techniques"] = s.cmsTechniques;
      j["cms_techniques_merged"] = s.cmsTechniquesMerged;
    }
    if (s.cmsCvTechniques == "triangle") {
      j["cms_pair_table_capacity"] = s.cmsPairTableCapacity;
      j["cms_pairs_used"] = s.cmsPairsUsed;
      j["cms_pair_samples"] = s.cmsPairSamples;
      j["cms_pair_refused_samples"] = s.cmsPairRefusedSamples;
      j["cms_pair_remainder_samples"] = s.cmsPairRemainderSamples;
      j["cms_pair_buffer_bytes"] = s.cmsPairBufferBytes;
    }
  }
  j["validation_errors"] = s.validationErrors;
  nlohmann::json passes = nlohmann::json::object();
  for (auto& [name, ms] : s.passMs) passes[name] = ms;
  j["gpu_pass_ms"] = passes;
  writeFileAtomically(path, j.dump(2) + "\n");
}

}  // namespace mixtrace
