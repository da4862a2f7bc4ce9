// Command-line parsing: defaults, both value syntaxes, every error class, help and version.
#include "session/options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "backend/renderer.h"
#include "session/option_table.h"
#include "session/option_values.h"
#include "util/error.h"

namespace mixtrace {
namespace {

ParsedCommandLine parse(std::initializer_list<const char*> args) {
  std::vector<const char*> argv = {"mixtrace"};
  argv.insert(argv.end(), args.begin(), args.end());
  return parseCommandLine(static_cast<int>(argv.size()), argv.data());
}

// Parses, expects an Error, and returns its message.
std::string errorOf(std::initializer_list<const char*> args) {
  try {
    parse(args);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return "";
}

void expectOneLineMentioning(const std::string& message, const std::string& needle) {
  EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "message: " << message;
  EXPECT_FALSE(message.empty());
}

TEST(Options, RenderDefaults) {
  const ParsedCommandLine parsed = parse({"render"});
  ASSERT_EQ(parsed.command, Command::Render);
  const RenderOptions& o = parsed.render;
  EXPECT_EQ(o.scene, "");
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(o.spp, -1);
  EXPECT_EQ(o.timeSeconds, -1.0);
  EXPECT_EQ(o.width, 320);
  EXPECT_EQ(o.height, 240);
  EXPECT_EQ(o.maxDepth, 5);
  EXPECT_EQ(o.method, "cms");
  EXPECT_EQ(o.backend, "vulkan");
  EXPECT_EQ(o.seed, 0u);
  EXPECT_EQ(o.statsPath, "");
  EXPECT_EQ(o.device, "");
  EXPECT_TRUE(o.png);
  EXPECT_FALSE(o.quiet);
  EXPECT_FALSE(o.validation);
  EXPECT_FALSE(o.generalPipelines);
  EXPECT_FALSE(o.variance);
  EXPECT_TRUE(o.relativeWeighting);
  EXPECT_TRUE(o.floatAtomics);
  EXPECT_EQ(o.trainSpp, 0);
}

TEST(Options, TrainingLengthAndErrorMap) {
  EXPECT_EQ(parse({"render", "--train-spp", "15"}).render.trainSpp, 15);
  expectOneLineMentioning(errorOf({"render", "--train-spp", "-3"}), "--train-spp");
  expectOneLineMentioning(errorOf({"render", "--train-spp", "many"}), "--train-spp");
  EXPECT_EQ(parse({"compare", "a.exr", "b.exr", "--error-only", "--error-map", "e.pfm"}).compare.errorMap, "e.pfm");
}

// --cells takes a count, kept as given, or the word auto (stored as 0); 0 itself is no count.
TEST(Options, CellsTakeACountOrAuto) {
  EXPECT_EQ(parse({"render", "--cells", "32"}).render.cells, 32);
  EXPECT_EQ(parse({"render", "--cells=16"}).render.cells, 16);
  EXPECT_EQ(parse({"render", "--cells", "auto"}).render.cells, 0);
  EXPECT_EQ(parse({"render"}).render.cells, 0);
  expectOneLineMentioning(errorOf({"render", "--cells", "0"}), "or auto");
  expectOneLineMentioning(errorOf({"render", "--cells", "Auto"}), "--cells");
  expectOneLineMentioning(errorOf({"render", "--cells", "5000"}), "1..4096");
}

TEST(Options, RelativeWeightingOnOff) {
  EXPECT_FALSE(parse({"render", "--relative-weighting", "off"}).render.relativeWeighting);
  EXPECT_TRUE(parse({"render", "--relative-weighting=on"}).render.relativeWeighting);
  expectOneLineMentioning(errorOf({"render", "--relative-weighting", "maybe"}), "--relative-weighting");
  EXPECT_FALSE(parse({"render", "--float-atomics", "off"}).render.floatAtomics);
  expectOneLineMentioning(errorOf({"render", "--float-atomics", "no"}), "--float-atomics");
}

TEST(Options, EveryOptionWithSeparateValues) {
  const ParsedCommandLine parsed =
      parse({"render", "scene.gltf", "--out", "x.exr", "--spp", "64", "--time", "2.5", "--width", "640", "--height",
             "480", "--max-depth", "8", "--method", "pt-uniform", "--backend", "cpu", "--seed", "4294967295",
             "--stats", "s.json", "--device", "llvmpipe", "--no-png", "-q", "--validation", "--general-pipelines",
             "--variance"});
  ASSERT_EQ(parsed.command, Command::Render);
  const RenderOptions& o = parsed.render;
  EXPECT_EQ(o.scene, "scene.gltf");
  EXPECT_EQ(o.out, "x.exr");
  EXPECT_EQ(o.spp, 64);
  EXPECT_DOUBLE_EQ(o.timeSeconds, 2.5);
  EXPECT_EQ(o.width, 640);
  EXPECT_EQ(o.height, 480);
  EXPECT_EQ(o.maxDepth, 8);
  EXPECT_EQ(o.method, "pt-uniform");
  EXPECT_EQ(o.backend, "cpu");
  EXPECT_EQ(o.seed, 4294967295u);
  EXPECT_EQ(o.statsPath, "s.json");
  EXPECT_EQ(o.device, "llvmpipe");
  EXPECT_FALSE(o.png);
  EXPECT_TRUE(o.quiet);
  EXPECT_TRUE(o.validation);
  EXPECT_TRUE(o.generalPipelines);
  EXPECT_TRUE(o.variance);
}

TEST(Options, EqualsSyntaxAndSceneAfterOptions) {
  const ParsedCommandLine parsed =
      parse({"render", "--spp=7", "--out=a=b.exr", "--max-depth=1", "--method=pt-power", "--quiet", "s.glb",
             "--device=0", "--time=0.25"});
  const RenderOptions& o = parsed.render;
  EXPECT_EQ(o.spp, 7);
  EXPECT_EQ(o.out, "a=b.exr");  // only the first '=' separates
  EXPECT_EQ(o.maxDepth, 1);
  EXPECT_EQ(o.method, "pt-power");
  EXPECT_TRUE(o.quiet);
  EXPECT_EQ(o.scene, "s.glb");
  EXPECT_EQ(o.device, "0");
  EXPECT_DOUBLE_EQ(o.timeSeconds, 0.25);
}

TEST(Options, DoubleDashMakesTheRestPositional) {
  EXPECT_EQ(parse({"render", "--", "-odd-name.gltf"}).render.scene, "-odd-name.gltf");
}

TEST(Options, HelpForms) {
  EXPECT_EQ(parse({}).command, Command::Help);
  EXPECT_EQ(parse({"--help"}).command, Command::Help);
  EXPECT_EQ(parse({"-h"}).command, Command::Help);
  EXPECT_EQ(parse({"help"}).command, Command::Help);
  EXPECT_EQ(parse({"render", "--help"}).command, Command::Help);
  EXPECT_EQ(parse({"render", "scene.gltf", "-h"}).command, Command::Help);
  // --help wins over a mistake elsewhere on the line.
  EXPECT_EQ(parse({"render", "--spp", "zero", "--help"}).command, Command::Help);
}

TEST(Options, Version) {
  EXPECT_EQ(parse({"--version"}).command, Command::Version);
  expectOneLineMentioning(errorOf({"--version", "extra"}), "extra");
}

TEST(Options, HelpTextDocumentsOptionsDefaultsAndExamples) {
  const std::string help = helpText();
  for (const char* needle :
       {"mixtrace render [SCENE] [options]", "--out", "--spp", "--time", "--width", "--height", "--max-depth",
        "--method", "--backend", "--seed", "--stats", "--device", "--no-png", "--quiet", "-q", "--validation",
        "--general-pipelines", "--variance", "--help", "--version", "pt-uniform", "pt-power", "vulkan", "cpu",
        "default: 16", "default: 320", "default: 240", "default: 5", "default: cms", "Mitsuba",
        "1 = only emitters seen", "2 = direct lighting", "5 = up to four bounces", "Examples:"})
    EXPECT_NE(help.find(needle), std::string::npos) << "help text lacks: " << needle;
  EXPECT_EQ(kDefaultSpp, 16);
  EXPECT_EQ(help.back(), '\n');
}

TEST(Options, UnknownOption) {
  expectOneLineMentioning(errorOf({"render", "--spd", "4"}), "--spd");
  expectOneLineMentioning(errorOf({"render", "--spd=4"}), "--spd");
  expectOneLineMentioning(errorOf({"render", "-x"}), "-x");
  expectOneLineMentioning(errorOf({"--spp", "4"}), "--spp");
}

TEST(Options, MissingValue) {
  for (const char* option : {"--out", "--spp", "--time", "--width", "--height", "--max-depth", "--method",
                             "--backend", "--seed", "--stats", "--device"}) {
    expectOneLineMentioning(errorOf({"render", option}), option);
    // Followed by another option: that option is not taken as the value.
    expectOneLineMentioning(errorOf({"render", option, "--quiet"}), option);
    // Empty value after '='.
    const std::string empty = std::string(option) + "=";
    expectOneLineMentioning(errorOf({"render", empty.c_str()}), option);
  }
}

TEST(Options, FlagGivenAValue) { expectOneLineMentioning(errorOf({"render", "--no-png=1"}), "--no-png"); }

TEST(Options, NonNumericValues) {
  expectOneLineMentioning(errorOf({"render", "--spp", "many"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--spp", "12abc"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--spp", "1.5"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--spp", " 4"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--time", "soon"}), "--time");
  expectOneLineMentioning(errorOf({"render", "--time", "nan"}), "--time");
  expectOneLineMentioning(errorOf({"render", "--time", "inf"}), "--time");
  expectOneLineMentioning(errorOf({"render", "--width", "wide"}), "--width");
  expectOneLineMentioning(errorOf({"render", "--height", "0x10"}), "--height");
  expectOneLineMentioning(errorOf({"render", "--max-depth", "deep"}), "--max-depth");
  expectOneLineMentioning(errorOf({"render", "--seed", "seed"}), "--seed");
}

TEST(Options, OutOfRangeNumbers) {
  expectOneLineMentioning(errorOf({"render", "--spp", "0"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--spp", "-3"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--spp", "99999999999999999999"}), "--spp");
  expectOneLineMentioning(errorOf({"render", "--time", "0"}), "--time");
  expectOneLineMentioning(errorOf({"render", "--time", "-1"}), "--time");
  expectOneLineMentioning(errorOf({"render", "--width", "0"}), "--width");
  expectOneLineMentioning(errorOf({"render", "--width", "16385"}), "--width");
  expectOneLineMentioning(errorOf({"render", "--height", "0"}), "--height");
  expectOneLineMentioning(errorOf({"render", "--height", "16385"}), "--height");
  expectOneLineMentioning(errorOf({"render", "--max-depth", "0"}), "--max-depth");
  expectOneLineMentioning(errorOf({"render", "--max-depth", "65"}), "--max-depth");
  expectOneLineMentioning(errorOf({"render", "--seed", "-1"}), "--seed");
  expectOneLineMentioning(errorOf({"render", "--seed", "4294967296"}), "--seed");
  // The bounds themselves are accepted.
  const RenderOptions edges =
      parse({"render", "--width", "16384", "--height", "1", "--max-depth", "64", "--spp", "1"}).render;
  EXPECT_EQ(edges.width, 16384);
  EXPECT_EQ(edges.height, 1);
  EXPECT_EQ(edges.maxDepth, 64);
  EXPECT_EQ(edges.spp, 1);
}

TEST(Options, UnknownMethodOrBackendListsTheValidOnes) {
  const std::string method = errorOf({"render", "--method", "bdpt"});
  expectOneLineMentioning(method, "--method");
  expectOneLineMentioning(method, "bdpt");
  for (const std::string& valid : knownMethods()) expectOneLineMentioning(method, valid);

  const std::string backend = errorOf({"render", "--backend=metal"});
  expectOneLineMentioning(backend, "--backend");
  expectOneLineMentioning(backend, "metal");
  expectOneLineMentioning(backend, "vulkan");
  expectOneLineMentioning(backend, "cpu");
}

TEST(Options, UnknownCommand) {
  expectOneLineMentioning(errorOf({"draw"}), "draw");
  expectOneLineMentioning(errorOf({"draw"}), "compare");
  // A scene given without the command gets a hint.
  expectOneLineMentioning(errorOf({"scene.gltf"}), "mixtrace render scene.gltf");
}

TEST(Options, TwoScenePaths) {
  const std::string message = errorOf({"render", "a.gltf", "--spp", "4", "b.gltf"});
  expectOneLineMentioning(message, "a.gltf");
  expectOneLineMentioning(message, "b.gltf");
}

TEST(Options, CompareDefaultsAndEveryOption) {
  ParsedCommandLine parsed = parse({"compare", "a.exr", "b.exr"});
  ASSERT_EQ(parsed.command, Command::Compare);
  EXPECT_EQ(parsed.compare.a, "a.exr");
  EXPECT_EQ(parsed.compare.b, "b.exr");
  EXPECT_DOUBLE_EQ(parsed.compare.alpha, 0.01);
  EXPECT_LT(parsed.compare.maxFailFraction, 0.0);
  EXPECT_EQ(parsed.compare.reportJson, "");
  EXPECT_FALSE(parsed.compare.quiet);
  EXPECT_FALSE(parsed.compare.errorOnly);
  EXPECT_TRUE(parse({"compare", "a.exr", "b.exr", "--error-only"}).compare.errorOnly);

  parsed = parse({"compare", "--alpha", "0.05", "a.exr", "--json=r.json", "-q", "b.exr", "--max-fail-fraction", "0.002"});
  ASSERT_EQ(parsed.command, Command::Compare);
  EXPECT_EQ(parsed.compare.a, "a.exr");
  EXPECT_EQ(parsed.compare.b, "b.exr");
  EXPECT_DOUBLE_EQ(parsed.compare.alpha, 0.05);
  EXPECT_DOUBLE_EQ(parsed.compare.maxFailFraction, 0.002);
  EXPECT_EQ(parsed.compare.reportJson, "r.json");
  EXPECT_TRUE(parsed.compare.quiet);
  EXPECT_EQ(parse({"compare", "a.exr", "--", "-b.exr"}).compare.b, "-b.exr");
  // The render options are not compare options.
  expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--spp", "4"}), "--spp");
  expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--spp", "4"}), "compare --help");
}

TEST(Options, CompareHelp) {
  EXPECT_EQ(parse({"compare", "--help"}).command, Command::Help);
  EXPECT_EQ(parse({"compare", "a.exr", "--alpha", "zero", "-h"}).command, Command::Help);
  const std::string help = helpText();
  for (const char* needle : {"mixtrace compare A.exr B.exr", "--alpha", "--json", "--max-fail-fraction",
                             "Exit status: 0 the images agree, 1 they differ, 2 error", "relMSE"})
    EXPECT_NE(help.find(needle), std::string::npos) << "help text lacks: " << needle;
  EXPECT_EQ(kCompareExitAgree, 0);
  EXPECT_EQ(kCompareExitDiffer, 1);
  EXPECT_EQ(kCompareExitError, 2);
}

TEST(Options, CompareNeedsExactlyTwoImages) {
  expectOneLineMentioning(errorOf({"compare"}), "two images");
  expectOneLineMentioning(errorOf({"compare", "a.exr"}), "two images");
  const std::string three = errorOf({"compare", "a.exr", "b.exr", "c.exr"});
  expectOneLineMentioning(three, "c.exr");
  expectOneLineMentioning(three, "two");
  expectOneLineMentioning(errorOf({"compare", "a.exr", ""}), "empty");
}

TEST(Options, CompareRejectsBadValues) {
  for (const char* alpha : {"0", "1", "-0.1", "1.5", "abc", "0.01x", "nan", "inf"})
    expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--alpha", alpha}), "--alpha");
  for (const char* fraction : {"-1", "1.01", "half"})
    expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--max-fail-fraction", fraction}),
                            "--max-fail-fraction");
  EXPECT_DOUBLE_EQ(parse({"compare", "a", "b", "--max-fail-fraction=0"}).compare.maxFailFraction, 0.0);
  expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--json"}), "--json");
  expectOneLineMentioning(errorOf({"compare", "a.exr", "b.exr", "--quiet=1"}), "--quiet");
}

// --look-from, --look-at, --up, --fov (issue 11, point 5): three finite float-range numbers, a
// field of view strictly between 0 and 180 degrees, and a frame that is a camera.
TEST(Options, CameraOptions) {
  const RenderOptions o =
      parse({"render", "--look-from", "1,2.5,-3", "--look-at=-1,0,1e3", "--up", "0,0,1", "--fov", "60"}).render;
  ASSERT_TRUE(o.camera.lookFrom && o.camera.lookAt && o.camera.up && o.camera.fovDegrees);
  EXPECT_EQ(*o.camera.lookFrom, (std::array<double, 3>{1.0, 2.5, -3.0}));
  EXPECT_EQ(*o.camera.lookAt, (std::array<double, 3>{-1.0, 0.0, 1000.0}));
  EXPECT_EQ(*o.camera.up, (std::array<double, 3>{0.0, 0.0, 1.0}));
  EXPECT_DOUBLE_EQ(*o.camera.fovDegrees, 60.0);
  EXPECT_FALSE(parse({"render"}).render.camera.any());
  EXPECT_TRUE(parse({"view", "--fov", "30"}).render.camera.any()) << "view takes render's camera options";

  for (const char* bad : {"1,2", "1,2,3,4", "1,,3", "a,b,c", "1,2,3x", " 1,2,3", "nan,0,0", "inf,0,0", "0,1e39,0",
                          "1e300,0,0", ""})
    expectOneLineMentioning(errorOf({"render", "--look-from", bad}), "--look-from");
  expectOneLineMentioning(errorOf({"render", "--look-at", "0,0"}), "--look-at");
  expectOneLineMentioning(errorOf({"render", "--up", "x,y,z"}), "--up");
  for (const char* bad : {"0", "180", "-10", "200", "nan", "inf", "45deg"})
    expectOneLineMentioning(errorOf({"render", "--fov", bad}), "--fov");
  EXPECT_DOUBLE_EQ(*parse({"render", "--fov", "179.5"}).render.camera.fovDegrees, 179.5);

  expectOneLineMentioning(errorOf({"render", "--look-from", "1,2,3", "--look-at", "1,2,3"}), "same point");
  expectOneLineMentioning(errorOf({"render", "--up", "0,0,0"}), "--up");
  expectOneLineMentioning(errorOf({"render", "--look-from", "0,5,0", "--look-at", "0,0,0", "--up", "0,1,0"}),
                          "parallel");
  expectOneLineMentioning(errorOf({"render", "--look-from", "0,5,0", "--look-at", "0,0,0", "--up", "0,-3,0"}),
                          "parallel");
  EXPECT_NO_THROW(parse({"render", "--look-from", "0,5,0", "--look-at", "0,0,0", "--up", "0,0,-1"}));
}

TEST(Options, HelpTextDocumentsCameraAndOutputFormats) {
  const std::string help = helpText();
  for (const char* needle : {"--look-from X,Y,Z", "--look-at X,Y,Z", "--up X,Y,Z", "--fov DEGREES", ".png or .jpg",
                             "Ctrl-C", "130"})
    EXPECT_NE(help.find(needle), std::string::npos) << "help text lacks: " << needle;
}

// --- The option table (session/option_table.h): the parser, --help and the defaults all come from
// its rows, so these tests iterate over the rows rather than name options.

// A command line of `command` (an OptionCommands bit) with `option` and `value` ("" for a flag).
std::string errorOfRowCommandLine(unsigned command, const std::string& option, const std::string& value) {
  std::vector<std::string> args = {"mixtrace", command == kForCompare ? "compare" : command == kForView ? "view" : "render"};
  if (command == kForCompare) args.insert(args.end(), {"a.exr", "b.exr"});
  args.push_back(value.empty() ? option : option + "=" + value);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    parseCommandLine(int(argv.size()), argv.data());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

unsigned firstCommandOf(const OptionRow& row) {
  for (unsigned c : {unsigned(kForRender), unsigned(kForView), unsigned(kForCompare)})
    if (row.takenBy(c)) return c;
  return 0;
}

// The help's entry of `row`: from its line to the next option's, with the wrapping undone.
std::string helpEntryOf(const std::string& help, const OptionRow& row) {
  std::string label = row.shortName ? std::string(row.shortName) + ", " : "";
  label += row.name;
  if (row.placeholder) label += std::string(" ") + row.placeholder;
  const std::string compare = row.takenBy(kForCompare) ? "\nCompare (" : "";
  const size_t section = compare.empty() ? 0 : help.find(compare);
  const size_t begin = help.find("\n  " + label, section == std::string::npos ? 0 : section);
  if (begin == std::string::npos) return "";
  size_t end = help.find("\n  -", begin + 1);
  const size_t blank = help.find("\n\n", begin + 1);
  if (blank < end) end = blank;
  std::string entry = help.substr(begin + 1, end - begin - 1);
  std::string flat;
  for (size_t i = 0; i < entry.size(); ++i) {
    if (entry[i] == '\n') {
      while (i + 1 < entry.size() && entry[i + 1] == ' ') ++i;
      flat += ' ';
    } else {
      flat += entry[i];
    }
  }
  return flat;
}

TEST(OptionTable, HelpListsEveryOptionWithItsDefault) {
  const std::string help = helpText();
  for (const OptionRow& row : optionTable()) {
    const std::string entry = helpEntryOf(help, row);
    ASSERT_FALSE(entry.empty()) << "--help has no entry for " << row.name;
    if (!row.shownDefault().empty())
      EXPECT_NE(entry.find("default: " + row.shownDefault()), std::string::npos)
          << row.name << "'s entry lacks its default '" << row.shownDefault() << "': " << entry;
    const std::string range = rangeText(row);
    if (row.kind == ValueKind::Integer || row.kind == ValueKind::Number)
      EXPECT_NE(entry.find(range), std::string::npos) << row.name << "'s entry lacks its range " << range << ": " << entry;
  }
}

TEST(OptionTable, ValuesOutsideEachRangeAreRefusedNamingTheRange) {
  int checked = 0;
  for (const OptionRow& row : optionTable()) {
    const unsigned command = firstCommandOf(row);
    const std::string name = row.name;
    const auto refused = [&](const std::string& value, const std::string& needle) {
      const std::string message = errorOfRowCommandLine(command, name, value);
      expectOneLineMentioning(message, name);
      expectOneLineMentioning(message, needle);
      ++checked;
    };
    const auto accepted = [&](const std::string& value) {
      EXPECT_EQ(errorOfRowCommandLine(command, name, value), "") << name << " " << value;
    };
    switch (row.kind) {
      case ValueKind::Integer:
        refused(std::to_string(row.minInteger - 1), expectedValue(row));
        if (row.maxInteger < 0x7fffffffffffffffLL) refused(std::to_string(row.maxInteger + 1), expectedValue(row));
        EXPECT_NE(expectedValue(row).find(std::to_string(row.minInteger)), std::string::npos) << name;
        accepted(std::to_string(row.minInteger));
        accepted(std::to_string(row.maxInteger));
        break;
      case ValueKind::Number: {
        refused(std::to_string(row.minNumber - 1), expectedValue(row));
        if (std::isfinite(row.maxNumber)) refused(std::to_string(row.maxNumber + 1), expectedValue(row));
        if (row.openRange) refused(std::to_string(row.minNumber), expectedValue(row));
        else accepted(std::to_string(row.minNumber));
        refused("nan", expectedValue(row));
        break;
      }
      case ValueKind::Choice:
        refused("no-such-value", "no-such-value");
        for (const std::string& choice : row.choices) {
          expectOneLineMentioning(errorOfRowCommandLine(command, name, "no-such-value"), choice);
          accepted(choice);
        }
        break;
      case ValueKind::Vector3:
        refused("1,2", expectedValue(row));
        refused("1,2,1e39", expectedValue(row));
        break;
      case ValueKind::Text: refused("", "needs a value"); break;
      case ValueKind::Flag: refused("1", "takes no value"); break;
    }
  }
  EXPECT_GE(checked, int(optionTable().size()));
}

TEST(OptionTable, AnOptionGivenToTheWrongCommandIsRefused) {
  int checked = 0;
  for (const OptionRow& row : optionTable())
    for (unsigned command : {unsigned(kForRender), unsigned(kForView), unsigned(kForCompare)}) {
      if (findOptionRow(row.name, command)) continue;   // taken (by this row or its namesake)
      const std::string message = errorOfRowCommandLine(command, row.name, row.takesValue() ? "1" : "");
      const std::string commandName = command == kForCompare ? "compare" : command == kForView ? "view" : "render";
      expectOneLineMentioning(message, row.name);
      expectOneLineMentioning(message, "not " + commandName);
      ++checked;
    }
  EXPECT_GE(checked, 10);
  expectOneLineMentioning(errorOf({"view", "--time", "2"}), "--time is for render, not view");
  expectOneLineMentioning(errorOf({"render", "--script", "s.txt"}), "--script is for view, not render");
}

// The defaults are the table's, applied through each row's own parser, and the options that are
// renderer settings default to what a RenderSettings holds: one set of defaults.
TEST(OptionTable, DefaultsComeFromTheTableAndMatchTheRenderer) {
  for (const OptionRow& row : optionTable())
    if (!row.defaultValue.empty()) EXPECT_NO_THROW(parseOptionValue(row, row.defaultValue)) << row.name;
  const RenderOptions o;
  const RenderSettings s;
  EXPECT_EQ(uint32_t(o.width), s.width);
  EXPECT_EQ(uint32_t(o.height), s.height);
  EXPECT_EQ(uint32_t(o.maxDepth), s.maxDepth);
  EXPECT_EQ(o.seed, s.seed);
  // --cells defaults to auto (0 here), which setUpMethod resolves (cms/grid_resolution.h); a
  // RenderSettings always holds a resolution.
  EXPECT_EQ(o.cells, 0);
  EXPECT_GE(s.cells, 1u);
  EXPECT_EQ(o.relativeWeighting, s.relativeWeighting);
  EXPECT_EQ(o.floatAtomics, s.floatAtomics);
  EXPECT_EQ(uint32_t(o.trainSpp), s.trainSpp);
  EXPECT_EQ(o.generalPipelines, s.generalPipelines);
  EXPECT_EQ(o.maxClusters, 16);
  EXPECT_EQ(o.method, kDefaultMethod);
  EXPECT_DOUBLE_EQ(CompareOptions().alpha, 0.01);
  EXPECT_EQ(knownMethods().size(), methodTable().size());
}

}  // namespace
}  // namespace mixtrace
