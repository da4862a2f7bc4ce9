#pragma once
// Command-line grammar of the mixtrace binary:
//   mixtrace render [SCENE] [options]
//   mixtrace compare A.exr B.exr [options]
//   mixtrace view [SCENE] [options] [--script FILE]
//   mixtrace help | --help | -h        (also: mixtrace render --help)
//   mixtrace --version
//   mixtrace --list-devices           (the Vulkan devices --device can name)
// Parsing only: nothing here prints, touches files or resolves defaults that need the scene.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cms/methods.h"

namespace mixtrace {

enum class Command { Render, Compare, View, Help, Version, ListDevices };

// Samples per pixel used when neither --spp nor --time is given: render's sample target
// (session/sample_loop.h) and the help both read it.
constexpr int kDefaultSpp = 16;

// A camera set on the command line, as pbrt's LookAt and Mitsuba's sensor do (--look-from,
// --look-at, --up, --fov). Each value given replaces that part of the camera the scene would
// otherwise use (the file's, or the default framing); session/scene_camera.h combines them.
struct CameraOptions {
  std::optional<std::array<double, 3>> lookFrom, lookAt, up;
  std::optional<double> fovDegrees;   // vertical field of view, in (0, 180)
  bool any() const { return lookFrom || lookAt || up || fovDegrees; }
};

// The options of render and view. Constructed with every option at its default: the option
// table's (session/option_table.cpp), the one place a default is written. Fields without a row
// default (spp, time, the paths) start unset.
// The largest --width / --height (and film side the file's aspect ratio may choose).
constexpr int kMaxImageSide = 16384;

struct RenderOptions {
  RenderOptions();
  std::string scene;             // empty -> default scene (resolved by the caller)
  std::string out;               // --out; empty -> "<scene stem>.exr" in the current directory; the
                                 // extension picks the format (output/render_output.h)
  int spp = -1;                  // --spp; -1: not given
  double timeSeconds = -1.0;     // --time; -1: not given; with spp too, stop at whichever comes first
  int width, height;             // --width, --height
  bool widthGiven = false;       // whether --width / --height were given (else the file camera's
  bool heightGiven = false;      // aspectRatio may decide the other side: applyFileAspectRatio)
  int maxDepth;                  // --max-depth: Mitsuba convention, >= 1
  std::string method;            // --method: a name of the method table (cms/methods.h)
  std::string backend;           // --backend: vulkan | cpu
  uint32_t seed;                 // --seed
  std::string statsPath;         // --stats FILE.json
  std::string device;            // --device INDEX|NAME-SUBSTRING; empty = first suitable device
  bool png = true;               // --no-png disables the preview beside an EXR
  bool quiet = false;            // -q/--quiet
  bool validation = false;       // --validation: Vulkan validation layer
  bool generalPipelines = false; // --general-pipelines: no specialisation on scene features
  std::string schedule = "auto"; // --schedule auto|wavefront|fused (Vulkan)
  bool variance = false;         // --variance: also write per-pixel variance of the mean
  int maxClusters;               // --max-clusters: CMS light clusters (techniques)
  int cells;                     // --cells: CMS cells along the longest scene axis; 0 = auto
                                 // (resolved by setUpMethod, cms/grid_resolution.h)
  bool perTriangleCv;            // --cv-techniques triangle|cluster: control-variate granularity
  int maxTechniques;             // --max-techniques: the control variate's technique budget
  int pairTableSlots;            // --pair-table-slots: the pair table's size (0 = automatic; testing aid)
  bool relativeWeighting;        // --relative-weighting on|off: CMS statistics weighting
                                 // (docs/estimator.md §5)
  int trainSpp;                  // --train-spp N: no CMS solve after N spp (0 = no limit)
  bool trainOnce;                // --training paper: one CMS solve after --train-spp (16) samples
  bool floatAtomics;             // --float-atomics on|off: CMS statistics with float atomics or CAS loops
  std::string assetRoot;         // --asset-root DIR: external scene files may lie under DIR (default: scene's folder)
  CameraOptions camera;          // --look-from, --look-at, --up, --fov
  std::string env;               // --env FILE|none; empty: the default (session/scene_environment.h)
  std::optional<std::array<double, 3>> envColor;   // --env-color R,G,B
  double envScale;               // --env-scale
  double envRotateDegrees;       // --env-rotate
  std::string aov;               // --aov albedo,normal,depth (any of them); empty: none
};

// `mixtrace compare`: a statistical test of whether two renders (written with --variance) estimate
// the same image; see compare/image_compare.h for the rule. Constructed at the table's defaults.
struct CompareOptions {
  CompareOptions();
  std::string a, b;              // the two EXR files; B is the reference for relMSE
  double alpha;                  // --alpha: family-wise significance, in (0, 1)
  double maxFailFraction = -1;   // --max-fail-fraction: tolerated failing fraction; < 0 = default rule
  std::string reportJson;        // --json FILE: write the full result as JSON
  bool quiet = false;            // -q/--quiet: no summary line, only the exit code
  bool errorOnly = false;        // --error-only: print relMSE of A against B; no variance needed
  std::string errorMap;          // --error-map FILE.pfm: write A's per-pixel relative squared error
};

// Exit codes of `mixtrace compare` (documented in --help), like diff(1).
constexpr int kCompareExitAgree = 0;
constexpr int kCompareExitDiffer = 1;
constexpr int kCompareExitError = 2;
constexpr int kCompareExitInconclusive = 3;   // no difference found, but too little power to tell

struct ParsedCommandLine {
  Command command = Command::Help;
  RenderOptions render;          // render, and view (which takes most of the same options)
  CompareOptions compare;
  std::string viewScript;        // view --script FILE: replayed input (host/viewer/input.h)
};

// argv[0] is the program name and is ignored. Throws mixtrace::Error with a one-line message
// naming the offending option or argument. Without any arguments the result is Command::Help.
ParsedCommandLine parseCommandLine(int argc, const char* const* argv);

// The full text printed by --help (ends with a newline).
std::string helpText();

// The values --method accepts: the names of the method table (cms/methods.h), in its order.
const std::vector<std::string>& knownMethods();

}  // namespace mixtrace
