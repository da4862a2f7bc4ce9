#include "scene/light_selection.h"

namespace mixtrace {
namespace {

// Fills pmf/cdf from unnormalised weights; uniform when all weights are zero. In double, and
// rounded to float per entry, as the GPU reads them.
void setSelection(std::vector<shared::LightSelectionGpu>& lights, const std::vector<double>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  double cdf = 0.0;
  for (size_t i = 0; i < lights.size(); ++i) {
    double pmf = total > 0.0 ? weights[i] / total : 1.0 / double(lights.size());
    cdf += pmf;
    lights[i].pmf = float(pmf);
    lights[i].cdf = float(cdf);
  }
  // The last CDF entry is exactly 1 so that u in [0, 1) always finds a light.
  if (!lights.empty()) lights.back().cdf = 1.0f;
}

}  // namespace

std::vector<shared::LightSelectionGpu> buildLightSelection(const LightSet& set, LightSelection selection) {
  std::vector<shared::LightSelectionGpu> lights(set.lights.size());
  // Without clusters every light is its own technique (methods with clusters overwrite these).
  for (uint32_t i = 0; i < lights.size(); ++i) {
    lights[i].cluster = i;
    lights[i].clusterPmf = 1.0f;
  }
  std::vector<double> weights;
  if (selection == LightSelection::Power || selection == LightSelection::Bvh) weights = set.power;
  else
    for (const shared::LightGpu& l : set.lights) weights.push_back(uniformSelectionWeight(l));
  setSelection(lights, weights);
  return lights;
}

}  // namespace mixtrace
