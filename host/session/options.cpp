// The grammar of the command line: which command, then its options and positional arguments. What
// each option is (its value, range, default) is the option table's (session/option_table.h).
#include "session/options.h"

#include <cctype>

#include "session/option_table.h"
#include "session/option_values.h"
#include "session/scene_camera.h"
#include "util/error.h"

namespace mixtrace {
namespace {

// Every row that `command` takes, at its default, into `to` (RenderOptions' and CompareOptions'
// constructors).
void applyDefaults(unsigned command, OptionDestination to) {
  for (const OptionRow& row : optionTable())
    if (row.takenBy(command) && !row.defaultValue.empty()) row.store(to, parseOptionValue(row, row.defaultValue));
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

// The row `name` names for `command`, or an Error saying it is unknown or another command's.
const OptionRow& rowFor(const std::string& name, unsigned command, const std::string& commandName) {
  if (const OptionRow* row = findOptionRow(name, command)) return *row;
  const std::string seeHelp = " (see 'mixtrace " + commandName + " --help')";
  if (const OptionRow* other = findOptionRowOfAnyCommand(name))
    throw Error("option " + std::string(other->name) + " is for " + commandsOf(*other) + ", not " + commandName +
                seeHelp);
  throw Error("unknown option '" + name + "'" + seeHelp);
}

// The shared grammar of a command's arguments: its options ("--opt value", "--opt=value", short
// flags), "--" ending the options, and everything else handed to `positional` in order.
template <typename Positional>
void parseArguments(const std::vector<std::string>& args, unsigned command, const std::string& commandName,
                    OptionDestination to, Positional positional) {
  bool onlyPositionals = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!onlyPositionals && arg == "--") {
      onlyPositionals = true;
      continue;
    }
    if (onlyPositionals || !looksLikeOption(arg)) {
      positional(arg);
      continue;
    }
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
    const OptionRow& row = rowFor(name, command, commandName);
    if (!row.takesValue()) {
      if (hasInlineValue) throw Error("option " + std::string(row.name) + " takes no value");
    } else {
      if (!hasInlineValue) {
        if (i + 1 >= args.size() || looksLikeOption(args[i + 1]))
          throw Error("option " + std::string(row.name) + " needs a value");
        value = args[++i];
      }
      if (value.empty()) throw Error("option " + std::string(row.name) + " needs a value");
    }
    row.store(to, parseOptionValue(row, value));
  }
}

// render and view: the same options (view's own and render's alone told apart by the table), one
// scene path.
ParsedCommandLine parseRenderOrView(const std::vector<std::string>& args, Command command) {
  ParsedCommandLine result;
  result.command = asksForHelp(args) ? Command::Help : command;
  if (result.command == Command::Help) return result;

  RenderOptions& options = result.render;
  const bool view = command == Command::View;
  const std::string commandName = view ? "view" : "render";
  OptionDestination to;
  to.render = &options;
  to.viewScript = &result.viewScript;
  parseArguments(args, view ? kForView : kForRender, commandName, to, [&](const std::string& arg) {
    if (!options.scene.empty())
      throw Error("two scene paths given ('" + options.scene + "' and '" + arg + "'); " + commandName +
                  " takes one SCENE");
    if (arg.empty()) throw Error("empty scene path");
    options.scene = arg;
  });
  checkCameraOptions(options.camera);
  return result;
}

ParsedCommandLine parseCompare(const std::vector<std::string>& args) {
  ParsedCommandLine result;
  result.command = asksForHelp(args) ? Command::Help : Command::Compare;
  if (result.command == Command::Help) return result;

  CompareOptions& options = result.compare;
  OptionDestination to;
  to.compare = &options;
  int images = 0;
  parseArguments(args, kForCompare, "compare", to, [&](const std::string& arg) {
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

RenderOptions::RenderOptions() {
  OptionDestination to;
  to.render = this;
  applyDefaults(kForRenderAndView, to);
  widthGiven = heightGiven = false;   // the defaults went through the options' own setters
}

CompareOptions::CompareOptions() {
  OptionDestination to;
  to.compare = this;
  applyDefaults(kForCompare, to);
}

const std::vector<std::string>& knownMethods() {
  static const std::vector<std::string> names = findOptionRow("--method", kForRender)->choices;
  return names;
}

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
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "render") return parseRenderOrView(rest, Command::Render);
  if (command == "compare") return parseCompare(rest);
  if (command == "view") return parseRenderOrView(rest, Command::View);
  if (looksLikeOption(command))
    throw Error("unknown option '" + command + "' before a command (usage: mixtrace render [SCENE] [options])");
  if (endsWith(command, ".gltf") || endsWith(command, ".glb"))
    throw Error("unknown command '" + command + "' (did you mean 'mixtrace render " + command + "'?)");
  throw Error("unknown command '" + command + "' (commands: render, compare, view, help; see 'mixtrace --help')");
}

}  // namespace mixtrace
