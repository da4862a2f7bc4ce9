#include "session/option_table.h"

#include <climits>
#include <limits>
#include <utility>

#include "cms/methods.h"
#include "backend/renderer.h"
#include "session/options.h"

namespace mixtrace {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr long long kMaxDepthLimit = 64;

std::string onOff(bool on) { return on ? "on" : "off"; }

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const MethodInfo& m : methodTable()) names.emplace_back(m.name);
  return names;
}

// --method's lines under its description: each method with its summary (cms/methods.h).
std::string methodList() {
  std::string lines;
  for (const MethodInfo& m : methodTable()) {
    const std::string name = m.name;
    lines += "                         " + name + std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') +
             m.summary + "\n";
  }
  return lines;
}

// Row builders: one per kind, so that each row below reads as its name, value, range, default
// and help.
OptionRow flag(const char* name, unsigned commands, OptionGroup group, std::string help,
               void (*store)(OptionDestination&, const OptionValue&)) {
  OptionRow row{name, nullptr, nullptr, ValueKind::Flag, commands, group};
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow text(const char* name, const char* placeholder, unsigned commands, OptionGroup group, std::string help,
               void (*store)(OptionDestination&, const OptionValue&)) {
  OptionRow row{name, nullptr, placeholder, ValueKind::Text, commands, group};
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow integer(const char* name, const char* placeholder, long long lo, long long hi, std::string defaultValue,
                  OptionGroup group, std::string help, void (*store)(OptionDestination&, const OptionValue&)) {
  OptionRow row{name, nullptr, placeholder, ValueKind::Integer, kForRenderAndView, group};
  row.minInteger = lo;
  row.maxInteger = hi;
  row.defaultValue = std::move(defaultValue);
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow number(const char* name, const char* placeholder, double lo, double hi, bool open, unsigned commands,
                 OptionGroup group, std::string help, void (*store)(OptionDestination&, const OptionValue&)) {
  OptionRow row{name, nullptr, placeholder, ValueKind::Number, commands, group};
  row.minNumber = lo;
  row.maxNumber = hi;
  row.openRange = open;
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow choice(const char* name, const char* placeholder, const char* noun, std::vector<std::string> choices,
                 std::string defaultValue, OptionGroup group, std::string help,
                 void (*store)(OptionDestination&, const OptionValue&)) {
  OptionRow row{name, nullptr, placeholder, ValueKind::Choice, kForRenderAndView, group};
  row.choiceNoun = noun;
  row.choices = std::move(choices);
  row.defaultValue = std::move(defaultValue);
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow vector3(const char* name, std::string help, void (*store)(OptionDestination&, const OptionValue&),
                  OptionGroup group = OptionGroup::Camera, const char* placeholder = "X,Y,Z") {
  OptionRow row{name, nullptr, placeholder, ValueKind::Vector3, kForRenderAndView, group};
  row.help = std::move(help);
  row.store = store;
  return row;
}

OptionRow withShortName(OptionRow row, const char* shortName) {
  row.shortName = shortName;
  return row;
}

OptionRow withDefault(OptionRow row, std::string value) {
  row.defaultValue = std::move(value);
  return row;
}

OptionRow withDefaultNote(OptionRow row, std::string note) {
  row.defaultNote = std::move(note);
  return row;
}

// An Integer row that also takes `word`, stored as 0 ("choose for me").
OptionRow withZeroWord(OptionRow row, const char* word) {
  row.zeroWord = word;
  return row;
}

OptionRow withUnit(OptionRow row, const char* unit) {
  row.unit = unit;
  return row;
}

// The scene's files and what a render writes.
std::vector<OptionRow> inputOutputRows() {
  using G = OptionGroup;
  using D = OptionDestination;
  using V = OptionValue;
  return {
    withDefaultNote(text("--asset-root", "DIR", kForRenderAndView, G::Input,
                         "trusted scenes: the buffers and images a scene names may lie anywhere under DIR",
                         [](D& d, const V& v) { d.render->assetRoot = v.text; }),
                    "only under the scene's own folder"),

    // The environment light (session/scene_environment.h)
    withDefaultNote(text("--env", "FILE|none", kForRenderAndView, G::Input,
                         "environment light: an equirectangular map of radiance (.exr, .hdr or .pfm; +Y up, "
                         "the map's centre towards +Z), or none for a black one",
                         [](D& d, const V& v) { d.render->env = v.text; }),
                    "none, or a uniform white environment of radiance 1 for a scene without lights"),
    vector3("--env-color", "a uniform environment of this linear RGB radiance instead of a map (each >= 0)",
            [](D& d, const V& v) { d.render->envColor = v.vector; }, G::Input, "R,G,B"),
    withDefault(number("--env-scale", "S", 0.0, kInfinity, false, kForRenderAndView, G::Input,
                       "multiplies the environment's radiance, {range}",
                       [](D& d, const V& v) { d.render->envScale = v.number; }),
                "1"),
    withUnit(withDefault(number("--env-rotate", "DEGREES", -360.0, 360.0, false, kForRenderAndView, G::Input,
                                "turns the environment about +Y (right-handed), {range}",
                                [](D& d, const V& v) { d.render->envRotateDegrees = v.number; }),
                         "0"),
             "degrees"),

    // Output
    withDefaultNote(text("--out", "FILE", kForRenderAndView, G::Output,
                         "image to write; its extension sets the format:\n.exr (default: {default}) float RGB "
                         "with spp, render time, method, estimator and scene in the header, and the 8-bit sRGB "
                         "preview FILE.png beside it;\n.png or .jpg: that tonemapped image only",
                         [](D& d, const V& v) { d.render->out = v.text; }),
                    "<scene stem>.exr in the current directory"),
    flag("--no-png", kForRenderAndView, G::Output, "do not write the PNG preview beside an EXR",
         [](D& d, const V&) { d.render->png = false; }),
    flag("--variance", kForRenderAndView, G::Output,
         "also store each pixel's standard error of the mean (sqrt of its variance), as EXR channels "
         "standardError.R, standardError.G, standardError.B",
         [](D& d, const V&) { d.render->variance = true; }),
    text("--aov", "LIST", kForRender, G::Output,
         "also write the first hit's albedo, normal and/or depth (comma-separated), averaged over each "
         "pixel's samples, as EXR channels albedo.R/G/B, normal.X/Y/Z, depth.Z (what denoisers take)",
         [](D& d, const V& v) { d.render->aov = v.text; }),
    text("--stats", "FILE.json", kForRender, G::Output, "write render statistics (timings, sample counts)",
         [](D& d, const V& v) { d.render->statsPath = v.text; }),
    withShortName(flag("--quiet", kForRenderAndView, G::Output,
                       "no progress or information lines (errors still go to stderr)",
                       [](D& d, const V&) { d.render->quiet = true; }),
                  "-q"),
  };
}

// The camera (checked as a whole in checkCameraOptions, session/scene_camera.h).
std::vector<OptionRow> cameraRows() {
  using G = OptionGroup;
  using D = OptionDestination;
  using V = OptionValue;
  return {
    vector3("--look-from", "where the camera is", [](D& d, const V& v) { d.render->camera.lookFrom = v.vector; }),
    vector3("--look-at", "the point it looks at (not --look-from)",
            [](D& d, const V& v) { d.render->camera.lookAt = v.vector; }),
    withDefaultNote(vector3("--up", "up direction, not parallel to the view direction",
                            [](D& d, const V& v) { d.render->camera.up = v.vector; }),
                    "the file's camera's, or 0,1,0"),
    withUnit(number("--fov", "DEGREES", 0.0, 180.0, true, kForRenderAndView, G::Camera,
                    "vertical field of view, {range}",
                    [](D& d, const V& v) { d.render->camera.fovDegrees = v.number; }),
             "degrees"),
  };
}

// What is rendered and how. The options that are settings of the renderer take its defaults
// (backend/renderer.h), so that a renderer built without the command line (the tests build many)
// renders what `render` does.
std::vector<OptionRow> samplingRows() {
  using G = OptionGroup;
  using D = OptionDestination;
  using V = OptionValue;
  const RenderSettings r{};
  return {
    withDefaultNote(integer("--spp", "N", 1, INT_MAX, "", G::Sampling, "samples per pixel, {range}",
                            [](D& d, const V& v) { d.render->spp = int(v.integer); }),
                    std::to_string(kDefaultSpp) + " when neither --spp nor --time is given"),
    withUnit(number("--time", "SECONDS", 0.0, kInfinity, true, kForRender, G::Sampling,
                    "render for SECONDS ({range}) of wall time; with --spp as well, stop at whichever limit "
                    "comes first",
                    [](D& d, const V& v) { d.render->timeSeconds = v.number; }),
             "seconds"),
    integer("--width", "W", 1, kMaxImageSide, std::to_string(r.width), G::Sampling,
            "image width in pixels, {range}; given alone (or with neither), the other side follows the file camera's aspectRatio where it has one", [](D& d, const V& v) {
              d.render->width = int(v.integer);
              d.render->widthGiven = true;
            }),
    integer("--height", "H", 1, kMaxImageSide, std::to_string(r.height), G::Sampling,
            "image height in pixels, {range}", [](D& d, const V& v) {
              d.render->height = int(v.integer);
              d.render->heightGiven = true;
            }),
    integer("--max-depth", "D", 1, kMaxDepthLimit, std::to_string(r.maxDepth), G::Sampling,
            "longest path, in segments, {range} (default: {default}).\nMitsuba's convention: 1 = only emitters "
            "seen directly, 2 = direct lighting,\n5 = up to four bounces",
            [](D& d, const V& v) { d.render->maxDepth = int(v.integer); }),
    integer("--seed", "S", 0, 0xffffffffLL, std::to_string(r.seed), G::Sampling, "random seed, {range}",
            [](D& d, const V& v) { d.render->seed = uint32_t(v.integer); }),
    integer("--max-clusters", "N", 1, 32, "16", G::Sampling,
            "learned/cv/cms: light clusters, one technique each, {range}",
            [](D& d, const V& v) { d.render->maxClusters = int(v.integer); }),
    choice("--cv-techniques", "triangle|cluster", "granularity", {"triangle", "cluster"},
           r.perTriangleCv ? "triangle" : "cluster", G::Sampling,
           "cv/cms: one control-variate coefficient per emissive triangle (and punctual light), or per\n"
           "light cluster (the former per-cluster control variate, for comparisons)",
           [](D& d, const V& v) { d.render->perTriangleCv = v.text == "triangle"; }),
    integer("--max-techniques", "N", shared::kMaxClusters, 1 << 24, std::to_string(kDefaultMaxTechniques),
            G::Sampling,
            "cv/cms with --cv-techniques triangle: at most N control-variate techniques, {range}; beyond it\n"
            "an area light's triangles merge into contiguous groups, and lights into their cluster at worst",
            [](D& d, const V& v) { d.render->maxTechniques = int(v.integer); }),
    integer("--pair-table-slots", "N", 0, 1 << 22, std::to_string(r.pairTableSlots), G::Sampling,
            "cv/cms with --cv-techniques triangle: slots of the (cell, technique) pair table, rounded up to\n"
            "a power of two, {range}; 0 = sized for the scene (testing aid: a tiny table refuses pairs)",
            [](D& d, const V& v) { d.render->pairTableSlots = int(v.integer); }),
    withZeroWord(integer("--cells", "N", 1, 4096, "auto", G::Sampling,
                         "learned/cv/cms: cells along the scene's longest axis ({range}), times 6 normal "
                         "directions; auto (the default) makes a cell about 16x16 pixels of footprint "
                         "where the camera's primary rays hit the scene, 4..256",
                         [](D& d, const V& v) { d.render->cells = int(v.integer); }),
                 "auto"),
    choice("--relative-weighting", "on|off", "setting", {"on", "off"}, onOff(r.relativeWeighting), G::Sampling,
           "learned/cv/cms: weight the cells' statistics by path throughput relative to the pixel",
           [](D& d, const V& v) { d.render->relativeWeighting = v.text == "on"; }),
    withDefaultNote(integer("--train-spp", "N", 0, INT_MAX, std::to_string(r.trainSpp), G::Sampling,
                            "learned/cv/cms: no solve after N spp, {range}; the rest of the render uses what was "
                            "learned by then",
                            [](D& d, const V& v) { d.render->trainSpp = int(v.integer); }),
                    std::to_string(r.trainSpp) + " = train through about the first half"),
    choice("--training", "doubling|paper", "schedule", {"doubling", "paper"}, r.trainOnce ? "paper" : "doubling",
           G::Sampling,
           "learned/cv/cms: solve after iterations of doubling length (1, 2, 4, ... spp), or once, as the paper "
           "does, after --train-spp samples (16 when not given)",
           [](D& d, const V& v) { d.render->trainOnce = v.text == "paper"; }),
    choice("--float-atomics", "on|off", "setting", {"on", "off"}, onOff(r.floatAtomics), G::Sampling,
           "learned/cv/cms on Vulkan: add the statistics with float atomics (on, where the device has them) "
           "or compare-and-swap loops",
           [](D& d, const V& v) { d.render->floatAtomics = v.text == "on"; }),
    [] {
      OptionRow row = choice("--method", "NAME", "method", methodNames(), kDefaultMethod, G::Sampling,
                             "light transport method (default: {default}):",
                             [](D& d, const V& v) { d.render->method = v.text; });
      row.details = methodList;
      return row;
    }(),
  };
}

// Where it runs.
std::vector<OptionRow> executionRows() {
  using G = OptionGroup;
  using D = OptionDestination;
  using V = OptionValue;
  return {
    choice("--backend", "NAME", "backend", {"vulkan", "cpu"}, "vulkan", G::Execution,
           "vulkan (the GPU wavefront renderer) or cpu (the multithreaded CPU reference)",
           [](D& d, const V& v) { d.render->backend = v.text; }),
    withDefaultNote(text("--device", "INDEX|NAME", kForRenderAndView, G::Execution,
                         "Vulkan device: its index in --list-devices (a number is always an index), or a "
                         "part of its name (any case) that matches one device only",
                         [](D& d, const V& v) { d.render->device = v.text; }),
                    "the first usable discrete GPU, else the first usable device"),
    flag("--validation", kForRenderAndView, G::Execution, "enable the Vulkan validation layer (slow)",
         [](D& d, const V&) { d.render->validation = true; }),
    choice("--schedule", "auto|wavefront|fused", "schedule", {"auto", "wavefront", "fused"}, "auto", G::Execution,
           "Vulkan: wavefront (a pass per stage and depth), fused (one dispatch traces whole paths, "
           "every method; not with --aov), or auto (GPUs: wavefront; CPU devices: the wavefront's "
           "first submission counts the rays per path, then fused where paths run deep)",
           [](D& d, const V& v) { d.render->schedule = v.text; }),
    flag("--general-pipelines", kForRenderAndView, G::Execution,
         "do not specialise the GPU pipelines on the scene's features (testing aid; same image)",
         [](D& d, const V&) { d.render->generalPipelines = true; }),
  };
}

// The options of one command only: view's script, compare's test.
std::vector<OptionRow> viewAndCompareRows() {
  using G = OptionGroup;
  using D = OptionDestination;
  using V = OptionValue;
  return {
    text("--script", "FILE", kForView, G::View,
         "replay input from FILE instead of waiting for a user (one event per line: frames N, key K,\n"
         "drag left|right DX DY, scroll DY, resize W H,\nscreenshot FILE.png, quit)",
         [](D& d, const V& v) { *d.viewScript = v.text; }),

    // Compare
    withDefault(number("--alpha", "A", 0.0, 1.0, true, kForCompare, G::Compare, "family-wise significance, {range}",
                       [](D& d, const V& v) { d.compare->alpha = v.number; }),
                "0.01"),
    number("--max-fail-fraction", "F", 0.0, 1.0, false, kForCompare, G::Compare,
           "tolerate up to F ({range}) of pixel-channels failing instead of max(2, 0.1%)",
           [](D& d, const V& v) { d.compare->maxFailFraction = v.number; }),
    text("--json", "FILE.json", kForCompare, G::Compare, "write the full result as JSON",
         [](D& d, const V& v) { d.compare->reportJson = v.text; }),
    withShortName(flag("--quiet", kForCompare, G::Compare, "no summary line; the exit status tells",
                       [](D& d, const V&) { d.compare->quiet = true; }),
                  "-q"),
    flag("--error-only", kForCompare, G::Compare,
         "only print 'relMSE X' of A against the reference B (no test, no variance channels needed; exit 0)",
         [](D& d, const V&) { d.compare->errorOnly = true; }),
    text("--error-map", "FILE.pfm", kForCompare, G::Compare,
         "with --error-only: also write A's per-pixel relative squared error (the terms relMSE averages) as a "
         "one-channel PFM image, for false-colour plots",
         [](D& d, const V& v) { d.compare->errorMap = v.text; }),
  };
}

std::vector<OptionRow> makeTable() {
  std::vector<OptionRow> table;
  for (std::vector<OptionRow> (*rows)() : {inputOutputRows, cameraRows, samplingRows, executionRows, viewAndCompareRows}) {
    std::vector<OptionRow> part = rows();
    table.insert(table.end(), part.begin(), part.end());
  }
  return table;
}

bool named(const OptionRow& row, const std::string& name) {
  return name == row.name || (row.shortName && name == row.shortName);
}

}  // namespace

const std::vector<OptionRow>& optionTable() {
  static const std::vector<OptionRow> table = makeTable();
  return table;
}

const OptionRow* findOptionRow(const std::string& name, unsigned command) {
  for (const OptionRow& row : optionTable())
    if (named(row, name) && row.takenBy(command)) return &row;
  return nullptr;
}

const OptionRow* findOptionRowOfAnyCommand(const std::string& name) {
  for (const OptionRow& row : optionTable())
    if (named(row, name)) return &row;
  return nullptr;
}

std::string commandsOf(const OptionRow& row) {
  std::vector<std::string> words;
  if (row.takenBy(kForRender)) words.emplace_back("render");
  if (row.takenBy(kForView)) words.emplace_back("view");
  if (row.takenBy(kForCompare)) words.emplace_back("compare");
  std::string text;
  for (size_t i = 0; i < words.size(); ++i)
    text += (i == 0 ? "" : i + 1 == words.size() ? " and " : ", ") + words[i];
  return text;
}

}  // namespace mixtrace
