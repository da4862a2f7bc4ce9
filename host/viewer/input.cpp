#include "viewer/input.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "cms/methods.h"
#include "util/error.h"

namespace mixtrace {

const std::vector<std::string>& knownKeyNames() {
  static const std::vector<std::string> names = [] {
    // The method keys come from the method table (cms/methods.h), plain and with shift.
    std::vector<std::string> keys;
    for (const char* prefix : {"", "shift+"})
      for (const MethodInfo& method : methodTable()) keys.push_back(prefix + std::string(1, method.viewerKey));
    for (const char* other : {"v", "g", "f1", "f2", "f3", "f4", "f5", "f6", "p", "r", "w", "a", "s", "d", "q", "e",
                              "escape"})
      keys.push_back(other);
    return keys;
  }();
  return names;
}

std::string canonicalKeyName(const std::string& written) {
  std::string name = written;
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (name == "esc") name = "escape";   // as the README, the banner and the key cap write it
  const auto& keys = knownKeyNames();
  if (std::find(keys.begin(), keys.end(), name) != keys.end()) return name;
  std::string valid;
  for (const std::string& key : keys) valid += (valid.empty() ? "" : " ") + key;
  throw Error("unknown key '" + written + "' (keys, in any case: " + valid + "; esc for escape)");
}

glm::vec3 flyDirectionOf(const std::string& key) {
  if (key == "w") return {0.0f, 0.0f, 1.0f};
  if (key == "s") return {0.0f, 0.0f, -1.0f};
  if (key == "d") return {1.0f, 0.0f, 0.0f};
  if (key == "a") return {-1.0f, 0.0f, 0.0f};
  if (key == "e") return {0.0f, 1.0f, 0.0f};
  if (key == "q") return {0.0f, -1.0f, 0.0f};
  return {0.0f, 0.0f, 0.0f};
}

std::deque<InputEvent> parseInputScript(const std::string& text, const std::string& fileName) {
  std::deque<InputEvent> events;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string verb;
    if (!(words >> verb)) continue;
    const std::string where = fileName + ":" + std::to_string(number) + ": ";
    InputEvent e;
    auto number2 = [&](float& a, float& b) {
      if (!(words >> a >> b)) throw Error(where + "'" + verb + "' needs two numbers");
    };
    if (verb == "frames") {
      e.kind = InputEvent::Kind::Frames;
      if (!(words >> e.x) || e.x < 1) throw Error(where + "'frames' needs a count >= 1");
    } else if (verb == "key") {
      e.kind = InputEvent::Kind::Key;
      if (!(words >> e.name)) throw Error(where + "'key' needs a key name");
      try {
        e.name = canonicalKeyName(e.name);
      } catch (const Error& unknown) {
        throw Error(where + unknown.what());
      }
    } else if (verb == "drag") {
      e.kind = InputEvent::Kind::Drag;
      if (!(words >> e.name) || (e.name != "left" && e.name != "right"))
        throw Error(where + "'drag' needs a button, left or right");
      number2(e.x, e.y);
    } else if (verb == "scroll") {
      e.kind = InputEvent::Kind::Scroll;
      if (!(words >> e.y)) throw Error(where + "'scroll' needs a number");
    } else if (verb == "resize") {
      e.kind = InputEvent::Kind::Resize;
      number2(e.x, e.y);
      if (e.x < 1 || e.y < 1 || e.x > 16384 || e.y > 16384) throw Error(where + "'resize' needs a size in 1..16384");
    } else if (verb == "screenshot") {
      e.kind = InputEvent::Kind::Screenshot;
      if (!(words >> e.name)) throw Error(where + "'screenshot' needs a file name");
    } else if (verb == "quit") {
      e.kind = InputEvent::Kind::Quit;
    } else {
      throw Error(where + "unknown command '" + verb + "' (frames, key, drag, scroll, resize, screenshot, quit)");
    }
    std::string extra;
    if (words >> extra) throw Error(where + "unexpected '" + extra + "'");
    events.push_back(e);
  }
  return events;
}

std::deque<InputEvent> loadInputScript(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read the script '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return parseInputScript(text.str(), path);
}

}  // namespace mixtrace
