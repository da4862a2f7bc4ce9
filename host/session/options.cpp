#include "session/options.h"

#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "compare/image_compare.h"
#include "session/scene_camera.h"
#include "util/error.h"

namespace mixtrace {
namespace {

// The names --method accepts, from the method table (cms/methods.h: add new estimators there).
const std::vector<std::string>& methodNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const MethodInfo& m : methodTable()) list.emplace_back(m.name);
    return list;
  }();
  return names;
}

const std::vector<std::string> kBackends = {"vulkan", "cpu"};

constexpr int kMaxImageSide = 16384;
constexpr int kMaxDepthLimit = 64;

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

bool contains(const std::vector<std::string>& items, const std::string& value) {
  for (const std::string& item : items)
    if (item == value) return true;
  return false;
}

// Strict decimal integer: the whole string must be the number (no spaces, no trailing text).
long long parseInteger(const std::string& option, const std::string& value, long long lo, long long hi,
                       const std::string& expectation) {
  const auto fail = [&] {
    throw Error("invalid value '" + value + "' for " + option + ": expected " + expectation);
  };
  if (value.empty() || std::isspace(static_cast<unsigned char>(value[0]))) fail();
  errno = 0;
  char* end = nullptr;
  const long long number = std::strtoll(value.c_str(), &end, 10);
  if (errno == ERANGE || end != value.c_str() + value.size()) fail();
  if (number < lo || number > hi) fail();
  return number;
}

double parsePositiveSeconds(const std::string& option, const std::string& value) {
  const auto fail = [&] {
    throw Error("invalid value '" + value + "' for " + option + ": expected a number of seconds > 0");
  };
  if (value.empty() || std::isspace(static_cast<unsigned char>(value[0]))) fail();
  errno = 0;
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (errno == ERANGE || end != value.c_str() + value.size()) fail();
  // strtod accepts "inf" and "nan"; neither is a usable time budget.
  if (!std::isfinite(number) || !(number > 0.0)) fail();
  return number;
}

// A strict decimal number (the whole string), finite and within float's range: camera values end
// up in float, where 1e300 would become infinity.
bool parseFloatRange(const std::string& text, double& number) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  errno = 0;
  char* end = nullptr;
  number = std::strtod(text.c_str(), &end);
  return errno != ERANGE && end == text.c_str() + text.size() && std::isfinite(number) && std::abs(number) <= FLT_MAX;
}

// "X,Y,Z": three numbers separated by commas, nothing else.
std::array<double, 3> parseVector(const std::string& option, const std::string& value) {
  std::array<double, 3> v{};
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = i < 2 ? value.find(',', start) : value.size();
    if (comma == std::string::npos || (i == 2 && value.find(',', start) != std::string::npos) ||
        !parseFloatRange(value.substr(start, comma - start), v[size_t(i)]))
      throw Error("invalid value '" + value + "' for " + option + ": expected three finite numbers X,Y,Z");
    start = comma + 1;
  }
  return v;
}

double parseFieldOfView(const std::string& option, const std::string& value) {
  double degrees = 0.0;
  if (!parseFloatRange(value, degrees) || !(degrees > 0.0 && degrees < 180.0))
    throw Error("invalid value '" + value + "' for " + option +
                ": expected a vertical field of view in degrees, between 0 and 180 (exclusive)");
  return degrees;
}

std::string oneOf(const std::string& option, const std::string& value, const std::vector<std::string>& valid,
                  const std::string& what) {
  if (!contains(valid, value))
    throw Error("unknown " + what + " '" + value + "' for " + option + " (valid: " + joined(valid) + ")");
  return value;
}

// A number in [lo, hi], or in (lo, hi) when `open`; the whole string must be the number.
double parseFraction(const std::string& option, const std::string& value, bool open) {
  const std::string expectation = open ? "a number between 0 and 1 (exclusive)" : "a number in 0..1";
  const auto fail = [&] { throw Error("invalid value '" + value + "' for " + option + ": expected " + expectation); };
  if (value.empty() || std::isspace(static_cast<unsigned char>(value[0]))) fail();
  errno = 0;
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (errno == ERANGE || end != value.c_str() + value.size() || !std::isfinite(number)) fail();
  if (open ? !(number > 0.0 && number < 1.0) : !(number >= 0.0 && number <= 1.0)) fail();
  return number;
}

// One row per option of a command whose options land in `Options`. `apply` receives the
// option's canonical long name for error messages.
template <typename Options>
struct OptionSpec {
  const char* name;
  const char* shortName;  // nullptr when there is none
  bool takesValue;
  void (*apply)(Options& options, const std::string& name, const std::string& value);
};

using RenderOptionSpec = OptionSpec<RenderOptions>;
using CompareOptionSpec = OptionSpec<CompareOptions>;

const RenderOptionSpec kOptionSpecs[] = {
    {"--out", nullptr, true, [](RenderOptions& o, const std::string&, const std::string& v) { o.out = v; }},
    {"--spp", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.spp = static_cast<int>(parseInteger(n, v, 1, 0x7fffffff, "an integer >= 1"));
     }},
    {"--time", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) { o.timeSeconds = parsePositiveSeconds(n, v); }},
    {"--width", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.width = static_cast<int>(parseInteger(n, v, 1, kMaxImageSide, "an integer in 1..16384"));
     }},
    {"--height", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.height = static_cast<int>(parseInteger(n, v, 1, kMaxImageSide, "an integer in 1..16384"));
     }},
    {"--max-depth", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.maxDepth = static_cast<int>(parseInteger(n, v, 1, kMaxDepthLimit, "an integer in 1..64"));
     }},
    {"--method", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.method = oneOf(n, v, methodNames(), "method");
     }},
    {"--backend", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.backend = oneOf(n, v, kBackends, "backend");
     }},
    {"--seed", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.seed = static_cast<uint32_t>(parseInteger(n, v, 0, 0xffffffffLL, "an integer in 0..4294967295"));
     }},
    {"--max-clusters", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.maxClusters = static_cast<int>(parseInteger(n, v, 1, 32, "an integer in 1..32"));
     }},
    {"--cells", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.cells = static_cast<int>(parseInteger(n, v, 1, 4096, "an integer in 1..4096"));
     }},
    {"--relative-weighting", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.relativeWeighting = oneOf(n, v, {"on", "off"}, "setting") == "on";
     }},
    {"--train-spp", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.trainSpp = static_cast<int>(parseInteger(n, v, 0, 1 << 30, "an integer >= 0"));
     }},
    {"--float-atomics", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) {
       o.floatAtomics = oneOf(n, v, {"on", "off"}, "setting") == "on";
     }},
    {"--stats", nullptr, true, [](RenderOptions& o, const std::string&, const std::string& v) { o.statsPath = v; }},
    {"--device", nullptr, true, [](RenderOptions& o, const std::string&, const std::string& v) { o.device = v; }},
    {"--no-png", nullptr, false, [](RenderOptions& o, const std::string&, const std::string&) { o.png = false; }},
    {"--quiet", "-q", false, [](RenderOptions& o, const std::string&, const std::string&) { o.quiet = true; }},
    {"--validation", nullptr, false,
     [](RenderOptions& o, const std::string&, const std::string&) { o.validation = true; }},
    {"--general-pipelines", nullptr, false,
     [](RenderOptions& o, const std::string&, const std::string&) { o.generalPipelines = true; }},
    {"--variance", nullptr, false, [](RenderOptions& o, const std::string&, const std::string&) { o.variance = true; }},
    {"--asset-root", nullptr, true,
     [](RenderOptions& o, const std::string&, const std::string& v) { o.assetRoot = v; }},
    // The camera (issue 11, point 5); checked as a whole in checkCameraOptions.
    {"--look-from", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) { o.camera.lookFrom = parseVector(n, v); }},
    {"--look-at", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) { o.camera.lookAt = parseVector(n, v); }},
    {"--up", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) { o.camera.up = parseVector(n, v); }},
    {"--fov", nullptr, true,
     [](RenderOptions& o, const std::string& n, const std::string& v) { o.camera.fovDegrees = parseFieldOfView(n, v); }},
};

const CompareOptionSpec kCompareOptionSpecs[] = {
    {"--alpha", nullptr, true,
     [](CompareOptions& o, const std::string& n, const std::string& v) { o.alpha = parseFraction(n, v, true); }},
    {"--max-fail-fraction", nullptr, true,
     [](CompareOptions& o, const std::string& n, const std::string& v) {
       o.maxFailFraction = parseFraction(n, v, false);
     }},
    {"--json", nullptr, true, [](CompareOptions& o, const std::string&, const std::string& v) { o.reportJson = v; }},
    {"--quiet", "-q", false, [](CompareOptions& o, const std::string&, const std::string&) { o.quiet = true; }},
    {"--error-only", nullptr, false,
     [](CompareOptions& o, const std::string&, const std::string&) { o.errorOnly = true; }},
    {"--error-map", nullptr, true,
     [](CompareOptions& o, const std::string&, const std::string& v) { o.errorMap = v; }},
};

template <typename Options, size_t N>
const OptionSpec<Options>* findOption(const OptionSpec<Options> (&specs)[N], const std::string& name) {
  for (const OptionSpec<Options>& spec : specs)
    if (name == spec.name || (spec.shortName && name == spec.shortName)) return &spec;
  return nullptr;
}

bool isHelpFlag(const std::string& arg) { return arg == "--help" || arg == "-h"; }

// "-x..." / "--x..." is an option; "-3" or "-.5" is a (negative) number, which then fails the
// range check of the option it was given to with a message naming that option.
bool looksLikeOption(const std::string& arg) {
  return arg.size() >= 2 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])) && arg[1] != '.';
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// --help anywhere (before "--") wins over everything else, even over mistakes elsewhere.
bool asksForHelp(const std::vector<std::string>& args) {
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (isHelpFlag(arg)) return true;
  }
  return false;
}

// The shared grammar of a command's arguments: options from `specs` ("--opt value", "--opt=value",
// short flags), "--" ending the options, and everything else handed to `positional` in order.
template <typename Options, size_t N, typename Positional>
void parseArguments(const std::vector<std::string>& args, const OptionSpec<Options> (&specs)[N], Options& options,
                    const std::string& commandName, Positional positional) {
  bool onlyPositionals = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!onlyPositionals && arg == "--") {
      onlyPositionals = true;
      continue;
    }
    if (!onlyPositionals && looksLikeOption(arg)) {
      // Split "--opt=value"; short options never carry an inline value.
      std::string name = arg;
      std::string value;
      bool hasInlineValue = false;
      const size_t equals = arg.find('=');
      if (arg.compare(0, 2, "--") == 0 && equals != std::string::npos) {
        name = arg.substr(0, equals);
        value = arg.substr(equals + 1);
        hasInlineValue = true;
      }
      const OptionSpec<Options>* spec = findOption(specs, name);
      if (!spec) throw Error("unknown option '" + name + "' (see 'mixtrace " + commandName + " --help')");
      if (!spec->takesValue) {
        if (hasInlineValue) throw Error("option " + std::string(spec->name) + " takes no value");
      } else if (!hasInlineValue) {
        if (i + 1 >= args.size() || looksLikeOption(args[i + 1]))
          throw Error("option " + std::string(spec->name) + " needs a value");
        value = args[++i];
      }
      if (spec->takesValue && value.empty()) throw Error("option " + std::string(spec->name) + " needs a value");
      spec->apply(options, spec->name, value);
      continue;
    }
    positional(arg);
  }
}

ParsedCommandLine parseRender(const std::vector<std::string>& args) {
  ParsedCommandLine result;
  result.command = asksForHelp(args) ? Command::Help : Command::Render;
  if (result.command == Command::Help) return result;

  RenderOptions& options = result.render;
  parseArguments(args, kOptionSpecs, options, "render", [&](const std::string& arg) {
    if (!options.scene.empty())
      throw Error("two scene paths given ('" + options.scene + "' and '" + arg + "'); render takes one SCENE");
    if (arg.empty()) throw Error("empty scene path");
    options.scene = arg;
  });
  checkCameraOptions(options.camera);
  return result;
}

// view: render's options, plus --script FILE.
ParsedCommandLine parseView(std::vector<std::string> args) {
  std::string script;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--script") {
      if (i + 1 >= args.size() || looksLikeOption(args[i + 1])) throw Error("option --script needs a value");
      script = args[i + 1];
      args.erase(args.begin() + long(i), args.begin() + long(i) + 2);
      --i;
    } else if (args[i].rfind("--script=", 0) == 0) {
      script = args[i].substr(9);
      if (script.empty()) throw Error("option --script needs a value");
      args.erase(args.begin() + long(i));
      --i;
    }
  }
  ParsedCommandLine result = parseRender(args);
  if (result.command == Command::Render) result.command = Command::View;
  result.viewScript = script;
  return result;
}

ParsedCommandLine parseCompare(const std::vector<std::string>& args) {
  ParsedCommandLine result;
  result.command = asksForHelp(args) ? Command::Help : Command::Compare;
  if (result.command == Command::Help) return result;

  CompareOptions& options = result.compare;
  int images = 0;
  parseArguments(args, kCompareOptionSpecs, options, "compare", [&](const std::string& arg) {
    if (arg.empty()) throw Error("empty image path");
    if (images == 2)
      throw Error("too many images ('" + arg + "' after '" + options.a + "' and '" + options.b +
                  "'); compare takes two: A.exr B.exr");
    (images++ == 0 ? options.a : options.b) = arg;
  });
  if (images < 2) throw Error("compare needs two images (usage: mixtrace compare A.exr B.exr [options])");
  return result;
}

}  // namespace

const std::vector<std::string>& knownMethods() { return methodNames(); }

ParsedCommandLine parseCommandLine(int argc, const char* const* argv) {
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) args.emplace_back(argv[i] ? argv[i] : "");

  ParsedCommandLine result;
  if (args.empty() || isHelpFlag(args[0]) || args[0] == "help") {
    result.command = Command::Help;
    return result;
  }
  const std::string& command = args[0];
  if (command == "--version") {
    if (args.size() > 1) throw Error("unexpected argument '" + args[1] + "' after --version");
    result.command = Command::Version;
    return result;
  }
  if (command == "--list-devices") {
    if (args.size() > 1) throw Error("unexpected argument '" + args[1] + "' after --list-devices");
    result.command = Command::ListDevices;
    return result;
  }
  if (command == "render") return parseRender(std::vector<std::string>(args.begin() + 1, args.end()));
  if (command == "compare") return parseCompare(std::vector<std::string>(args.begin() + 1, args.end()));
  if (command == "view") return parseView(std::vector<std::string>(args.begin() + 1, args.end()));
  if (looksLikeOption(command))
    throw Error("unknown option '" + command + "' before a command (usage: mixtrace render [SCENE] [options])");
  if (endsWith(command, ".gltf") || endsWith(command, ".glb"))
    throw Error("unknown command '" + command + "' (did you mean 'mixtrace render " + command + "'?)");
  throw Error("unknown command '" + command + "' (commands: render, compare, view, help; see 'mixtrace --help')");
}

std::string helpText() {
  const RenderOptions defaults;
  std::ostringstream text;
  text << "mixtrace " << MIXTRACE_VERSION
       << " - a physically based path tracer (glTF 2.0 in, OpenEXR out)\n"
          "\n"
          "Usage:\n"
          "  mixtrace render [SCENE] [options]  render SCENE (.gltf/.glb) to OpenEXR\n"
          "  mixtrace compare A.exr B.exr [options]\n"
          "                                     test whether two renders made with\n"
          "                                     --variance estimate the same image\n"
          "  mixtrace view [SCENE] [options]    open a window and watch SCENE converge\n"
          "  mixtrace help | --help | -h         print this text (or: render --help)\n"
          "  mixtrace --version                  print the version\n"
          "  mixtrace --list-devices             list the Vulkan devices: index, name,\n"
          "                                     type, driver, whether usable\n"
          "\n"
          "Without SCENE, the default scene shipped with mixtrace is rendered.\n"
          "Options take their value as '--opt value' or '--opt=value'.\n"
          "\n"
          "Input:\n"
          "  --asset-root DIR     trusted scenes: the buffers and images a scene names\n"
          "                       may lie anywhere under DIR (default: only under the\n"
          "                       scene's own folder)\n"
          "\n"
          "Output:\n"
          "  --out FILE           image to write; its extension sets the format:\n"
          "                       .exr (default: <scene stem>.exr in the current\n"
          "                       directory) float RGB with spp, render time,\n"
          "                       method, estimator and scene in the header, and\n"
          "                       the 8-bit sRGB preview FILE.png beside it;\n"
          "                       .png or .jpg: that tonemapped image only\n"
          "  --no-png             do not write the PNG preview beside an EXR\n"
          "  --variance           also store each pixel's standard error of the mean\n"
          "                       (sqrt of its variance), as EXR channels\n"
          "                       standardError.R, standardError.G, standardError.B\n"
          "  --stats FILE.json    write render statistics (timings, sample counts)\n"
          "  -q, --quiet          no progress or information lines (errors still\n"
          "                       go to stderr)\n"
          "  Outputs are checked before rendering (known format, directory\n"
          "  writable, no two the same file, none the scene or its files) and\n"
          "  written under a temporary name, renamed when complete. Ctrl-C (or\n"
          "  SIGTERM) stops after the sample pass in flight and writes what has\n"
          "  been rendered (the header and stats say how many spp), exit status\n"
          "  130 (143); a second one aborts at once.\n"
          "\n"
          "Camera (render, and where view starts): replaces the parts of the file's\n"
          "camera it sets; a file without one gets a default camera that frames\n"
          "the scene's bounds from outside (an info line says where it is):\n"
          "  --look-from X,Y,Z    where the camera is\n"
          "  --look-at X,Y,Z      the point it looks at (not --look-from)\n"
          "  --up X,Y,Z           up direction, not parallel to the view direction\n"
          "                       (default: the file's camera's, or 0,1,0)\n"
          "  --fov DEGREES        vertical field of view, 0 < DEGREES < 180\n"
          "\n"
          "Sampling:\n"
          "  --spp N              samples per pixel, N >= 1 (default: "
       << kDefaultSpp
       << " when neither\n"
          "                       --spp nor --time is given)\n"
          "  --time SECONDS       render for SECONDS (> 0) of wall time; with --spp\n"
          "                       as well, stop at whichever limit comes first\n"
          "  --width W            image width in pixels, 1..16384 (default: "
       << defaults.width
       << ")\n"
          "  --height H           image height in pixels, 1..16384 (default: "
       << defaults.height
       << ")\n"
          "  --max-depth D        longest path, in segments, 1..64 (default: "
       << defaults.maxDepth
       << ").\n"
          "                       Mitsuba's convention: 1 = only emitters seen\n"
          "                       directly, 2 = direct lighting,\n"
          "                       5 = up to four bounces\n"
          "  --seed S             random seed, 0..4294967295 (default: "
       << defaults.seed
       << ")\n"
          "  --max-clusters N     learned/cv/cms: light clusters, one technique each,\n"
          "                       1..32 (default: "
       << defaults.maxClusters
       << ")\n"
          "  --cells N            learned/cv/cms: cells along the scene's longest\n"
          "                       axis, times 6 normal directions (default: "
       << defaults.cells
       << ")\n"
          "  --relative-weighting on|off\n"
          "                       learned/cv/cms: weight the cells' statistics by\n"
          "                       path throughput relative to the pixel (default: on)\n"
          "  --train-spp N        learned/cv/cms: no solve after N spp; the rest of\n"
          "                       the render uses what was learned by then (default:\n"
          "                       0 = train through about the first half)\n"
          "  --float-atomics on|off\n"
          "                       learned/cv/cms on Vulkan: add the statistics with\n"
          "                       float atomics (on, where the device has them) or\n"
          "                       compare-and-swap loops (default: on)\n"
          "  --method NAME        light transport method (default: "
       << defaults.method << "):\n";
  for (const MethodInfo& m : methodTable()) {
    const std::string method = m.name;
    text << "                         " << method << std::string(method.size() < 12 ? 12 - method.size() : 1, ' ')
         << m.summary << "\n";
  }
  const std::string keys = viewerKeyRange();   // the viewer's method keys
  text << "\n"
          "Execution:\n"
          "  --backend NAME       vulkan (the GPU wavefront renderer) or cpu (the\n"
          "                       multithreaded CPU reference) (default: "
       << defaults.backend
       << ")\n"
          "  --device INDEX|NAME  Vulkan device: its index in --list-devices (a\n"
          "                       number is always an index), or a part of its name\n"
          "                       (any case) that matches one device only (default:\n"
          "                       the first usable discrete GPU, else the first\n"
          "                       usable device)\n"
          "  --validation         enable the Vulkan validation layer (slow)\n"
          "  --general-pipelines  do not specialise the GPU pipelines on the\n"
          "                       scene's features (testing aid; same image)\n"
          "\n"
          "View (mixtrace view [SCENE] [options]):\n"
          "  Renders progressively into a window with the same passes as render\n"
          "  and takes render's options (--width/--height: the film, shown scaled;\n"
          "  --spp N: stop accumulating at N; --out: where P saves). Keys: "
       << keys << "\n  method (" << joined(methodNames())
       << "); V split view of two\n"
          "  methods at equal time, shift+"
       << keys
       << " its right-hand method; G or F1-F6\n"
          "  view: image, variance, cells, alpha sum, likely light, cell samples;\n"
          "  P save EXR + PNG; R reset camera; Esc quit. Mouse: left drag orbit,\n"
          "  right drag pan, wheel zoom; W/A/S/D/Q/E fly.\n"
          "  --script FILE        replay input from FILE instead of waiting for a\n"
          "                       user (one event per line: frames N, key K,\n"
          "                       drag left|right DX DY, scroll DY, resize W H,\n"
          "                       screenshot FILE.png, quit)\n"
          "\n"
          "Compare (mixtrace compare A.exr B.exr [options]):\n"
          "  Both images need the variance channels written by render --variance.\n"
          "  Each pixel-channel is z-tested, z = (a - b) / sqrt(varA + varB), against\n"
          "  a threshold corrected for the number of pixel-channels; a few failures\n"
          "  (max(2, 0.1%)) are tolerated as heavy-tailed Monte Carlo outliers. Each\n"
          "  channel's image mean is z-tested too (catches small global biases).\n"
          "  Prints one line: verdict, fraction failing, relMSE of A against B,\n"
          "  per-channel mean ratios A/B and their z-scores. Render both with at\n"
          "  least 16 spp: below that the per-pixel z-scores are too heavy-tailed.\n"
          "  --alpha A            family-wise significance, 0 < A < 1 (default: "
       << CompareOptions().alpha
       << ")\n"
          "  --max-fail-fraction F\n"
          "                       tolerate up to F (0..1) of pixel-channels failing\n"
          "                       instead of max(2, 0.1%)\n"
          "  --json FILE.json     write the full result as JSON\n"
          "  -q, --quiet          no summary line; the exit status tells\n"
          "  --error-only         only print 'relMSE X' of A against the reference B\n"
          "                       (no test, no variance channels needed; exit 0)\n"
          "  --error-map FILE.pfm with --error-only: also write A's per-pixel\n"
          "                       relative squared error (the terms relMSE averages)\n"
          "                       as a one-channel PFM image, for false-colour plots\n"
          "  Inconclusive: no difference found, but the image-mean test would miss\n"
          "  a difference of "
       << std::lround(100 * kInconclusiveDifference) << "% in some channel more often than "
       << std::lround(100 * (1 - kDetectionPower))
       << "% of the time\n"
          "  (its variance is too large: render more spp or a larger image).\n"
          "  Exit status: "
       << kCompareExitAgree << " the images agree, " << kCompareExitDiffer << " they differ, " << kCompareExitError
       << " error (bad\n"
          "  arguments, unreadable file, no variance, different sizes), "
       << kCompareExitInconclusive << " inconclusive.\n"
          "\n"
          "Examples:\n"
          "  mixtrace render\n"
          "      the default scene, "
       << kDefaultSpp
       << " spp, to <default scene>.exr and .png\n"
          "  mixtrace render scenes/cornell_box.gltf --spp 256 --out cornell.exr\n"
          "  mixtrace render scene.glb --time 10 --width 640 --height 480\n"
          "  mixtrace render scene.glb --method=pt-uniform --backend=cpu --seed 7\n"
          "  mixtrace render room.gltf --look-from 0,1.5,2 --look-at 0,1,0 --fov 60\n"
          "  mixtrace compare new.exr reference.exr --json report.json\n";
  return text.str();
}

}  // namespace mixtrace
