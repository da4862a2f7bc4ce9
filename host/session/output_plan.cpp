#include "session/output_plan.h"

#include <filesystem>
#include <vector>

#include "session/scene_files.h"
#include "output/output_paths.h"
#include "output/render_output.h"
#include "util/error.h"

namespace mixtrace {
std::vector<std::string> parseAovList(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    const std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (name != "albedo" && name != "normal" && name != "depth")
      throw Error("--aov: '" + name + "' is not an AOV (albedo, normal, depth; comma-separated)");
    for (const std::string& seen : out)
      if (seen == name) throw Error("--aov: " + name + " is named twice");
    out.push_back(name);
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

namespace {

// The image and its preview, from --out (its extension decides the format).
OutputPlan imageOutputs(const std::string& image, const RenderOptions& o) {
  ImageFormat format;
  try {
    format = imageFormatOf(image);
  } catch (const Error& e) {
    throw Error(std::string("--out: ") + e.what());
  }
  if (o.variance && format != ImageFormat::Exr)
    throw Error("--variance needs an .exr --out ('" + image + "' would hold only the tonemapped image)");
  if (!o.aov.empty() && format != ImageFormat::Exr)
    throw Error("--aov needs an .exr --out ('" + image + "' would hold only the tonemapped image)");
  OutputPlan plan;
  if (!o.aov.empty()) plan.aovs = parseAovList(o.aov);
  plan.image = image;
  plan.preview = previewPathFor(image, o.png);
  return plan;
}

void checkFiles(const OutputPlan& plan, const std::string& scenePath, const std::string& environmentMap) {
  std::vector<NamedFile> outputs = {{"--out", plan.image}};
  if (!plan.preview.empty()) outputs.push_back({"the PNG preview beside --out", plan.preview});
  if (!plan.stats.empty()) outputs.push_back({"--stats", plan.stats});
  std::vector<NamedFile> inputs = {{"the scene", scenePath}};
  for (const std::string& file : filesReferencedByScene(scenePath)) inputs.push_back({"the scene's file", file});
  if (!environmentMap.empty() && environmentMap != "none") inputs.push_back({"--env", environmentMap});
  checkNoSharedFiles(outputs, inputs);
  for (const NamedFile& output : outputs) checkWritableOutput(output);
}

}  // namespace

OutputPlan planRenderOutputs(const RenderOptions& o, const std::string& scenePath) {
  OutputPlan plan = imageOutputs(o.out.empty() ? std::filesystem::path(scenePath).stem().string() + ".exr" : o.out, o);
  plan.stats = o.statsPath;
  checkFiles(plan, scenePath, o.env);
  return plan;
}

void checkViewerOutputs(const RenderOptions& o, const std::string& scenePath) {
  if (!o.out.empty()) checkFiles(imageOutputs(o.out, o), scenePath, o.env);
}

}  // namespace mixtrace
