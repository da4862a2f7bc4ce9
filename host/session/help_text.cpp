// `mixtrace --help`, generated from the option table (session/option_table.h): each option's line
// is its name and placeholder, then its description with its range and default, wrapped. Only the
// prose around the options (what each section is about, the examples) is written here.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cms/methods.h"
#include "compare/image_compare.h"
#include "session/option_table.h"
#include "session/option_values.h"
#include "session/options.h"

namespace mixtrace {
namespace {

constexpr size_t kWidth = 74;              // the longest wrapped line
constexpr size_t kDescriptionColumn = 23;  // where an option's description starts

// A space the wrapping does not break at (in "(default: 16)").
constexpr char kNoBreakSpace = '\x1f';

// `text` wrapped to kWidth, its first line continuing `line` (which may hold a prefix already),
// the following lines starting with `indent`. Words are split at spaces; '\n' forces a break.
std::string wrapped(std::string line, const std::string& text, const std::string& indent) {
  std::string out;
  bool lineHasWords = false;
  std::istringstream paragraphs(text);
  std::string paragraph;
  bool firstParagraph = true;
  while (std::getline(paragraphs, paragraph, '\n')) {
    if (!firstParagraph) {
      out += line + "\n";
      line = indent;
      lineHasWords = false;
    }
    firstParagraph = false;
    std::istringstream words(paragraph);
    std::string word;
    while (words >> word) {
      if (lineHasWords && line.size() + 1 + word.size() > kWidth) {
        out += line + "\n";
        line = indent;
        lineHasWords = false;
      }
      line += (lineHasWords ? " " : "") + word;
      lineHasWords = true;
    }
  }
  out += line + "\n";
  for (char& c : out)
    if (c == kNoBreakSpace) c = ' ';
  return out;
}

// A paragraph of prose, indented by `indent` on every line.
std::string prose(const std::string& text, const std::string& indent) { return wrapped(indent, text, indent); }

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

// The row's description: its help with the range and default filled in.
std::string description(const OptionRow& row) {
  std::string text = row.help;
  replaceAll(text, "{range}", rangeText(row));
  const std::string shown = row.shownDefault();
  if (text.find("{default}") != std::string::npos) replaceAll(text, "{default}", shown);
  else if (!shown.empty()) text += std::string(" (default:") + kNoBreakSpace + shown + ")";
  return text;
}

// "  --width W            image width in pixels, ..." wrapped; a name too long for the column
// gets a line of its own.
std::string optionEntry(const OptionRow& row) {
  std::string label = row.shortName ? std::string(row.shortName) + ", " : "";
  label += row.name;
  if (row.placeholder) label += std::string(" ") + row.placeholder;
  std::string line = "  " + label;
  const std::string indent(kDescriptionColumn, ' ');
  std::string entry;
  if (line.size() + 1 > kDescriptionColumn) {
    entry = line + "\n";
    line = indent;
  } else {
    line += std::string(kDescriptionColumn - line.size(), ' ');
  }
  entry += wrapped(line, description(row), indent);
  if (row.details) entry += row.details();
  return entry;
}

// The options render takes and view does not ("--stats and --time").
std::string renderOnlyOptions() {
  std::vector<std::string> names;
  for (const OptionRow& row : optionTable())
    if (row.takenBy(kForRender) && !row.takenBy(kForView)) names.emplace_back(row.name);
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return text;
}

// A section of --help: its heading (a line, or a paragraph ending in ':'), prose before its
// options (indented) and after them.
struct Section {
  OptionGroup group;
  std::string heading, before, after;
};

// What view does and its keys. Kept unbroken (tests/unit/cms/methods_test.cpp looks for them):
// "Keys: 1-5" ending its line, and "shift+1-5 its right-hand method".
std::string viewIntro() {
  const std::string keys = viewerKeyRange();   // the viewer's method keys
  const std::string nb(1, kNoBreakSpace);
  std::string methods;
  for (const MethodInfo& m : methodTable()) methods += (methods.empty() ? "" : ", ") + std::string(m.name);
  return "Renders progressively into a window with the same passes as render and takes render's options "
         "except " + renderOnlyOptions() +
         " (--width/--height: the film, shown scaled; --spp N: stop accumulating at N; --out: where P saves). "
         "Keys:" + nb + keys + "\nmethod (" + methods + "); V split view of two methods at equal time, shift+" +
         keys + nb + "its" + nb + "right-hand" + nb +
         "method; G or F1-F6 view: image, variance, cells, alpha sum, likely light, cell samples; P save EXR + "
         "PNG; R reset camera; Esc quit. Mouse: left drag orbit, right drag pan, wheel zoom; W/A/S/D/Q/E fly.";
}

std::vector<Section> sections() {
  return {
      {OptionGroup::Input, "Input:", "", ""},
      {OptionGroup::Output, "Output:", "",
       "Outputs are checked before rendering (known format, directory writable, no two the same file, none the "
       "scene or its files) and written under a temporary name, renamed when complete. Ctrl-C (or SIGTERM) "
       "stops after the sample pass in flight and writes what has been rendered (the header and stats say how "
       "many spp), exit status 130 (143); a second one aborts at once."},
      {OptionGroup::Camera,
       "Camera (render, and where view starts): replaces the parts of the file's camera it sets; a file without "
       "one gets a default camera that frames the scene's bounds from outside (an info line says where it is):",
       "", ""},
      {OptionGroup::Sampling, "Sampling:", "", ""},
      {OptionGroup::Execution, "Execution:", "", ""},
      {OptionGroup::View, "View (mixtrace view [SCENE] [options]):", viewIntro(), ""},
      {OptionGroup::Compare, "Compare (mixtrace compare A.exr B.exr [options]):",
       "Both images need the variance channels written by render --variance. Each pixel-channel is z-tested, "
       "z = (a - b) / sqrt(varA + varB), against a threshold corrected for the number of pixel-channels; a few "
       "failures (max(2, 0.1%)) are tolerated as heavy-tailed Monte Carlo outliers. Each channel's image mean "
       "is z-tested too (catches small global biases). Prints one line: verdict, fraction failing, relMSE of A "
       "against B, per-channel mean ratios A/B and their z-scores. Render both with at least 16 spp: below that "
       "the per-pixel z-scores are too heavy-tailed.",
       "Inconclusive: no difference found, but the image-mean test would miss a difference of " +
           std::to_string(std::lround(100 * kInconclusiveDifference)) + "% in some channel more often than " +
           std::to_string(std::lround(100 * (1 - kDetectionPower))) +
           "% of the time (its variance is too large: render more spp or a larger image).\nExit status: " +
           std::to_string(kCompareExitAgree) + " the images agree, " + std::to_string(kCompareExitDiffer) +
           " they differ, " + std::to_string(kCompareExitError) +
           " error (bad arguments, unreadable file, no variance, different sizes), " +
           std::to_string(kCompareExitInconclusive) + " inconclusive."},
  };
}

}  // namespace

std::string helpText() {
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
          "Options take their value as '--opt value' or '--opt=value'.\n";
  for (const Section& section : sections()) {
    text << "\n" << prose(section.heading, "");
    if (!section.before.empty()) text << prose(section.before, "  ");
    for (const OptionRow& row : optionTable())
      if (row.group == section.group) text << optionEntry(row);
    if (!section.after.empty()) text << prose(section.after, "  ");
  }
  text << "\n"
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
