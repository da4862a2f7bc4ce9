// The viewer's input scripts (host/viewer/input.h): every event kind parses, comments and blank
// lines are skipped, and a bad line is one error naming the file and line.
#include <gtest/gtest.h>

#include <algorithm>

#include "cms/methods.h"
#include "util/error.h"
#include "viewer/input.h"

namespace mixtrace {
namespace {

TEST(ViewerInput, ParsesEveryEvent) {
  const auto events = parseInputScript(
      "# a demo\nframes 3\nkey 5\nkey shift+2  # split\ndrag left 10 -4\n\nscroll 2\nresize 320 200\n"
      "screenshot a.png\nquit\n",
      "demo.txt");
  ASSERT_EQ(events.size(), 8u);
  using Kind = InputEvent::Kind;
  EXPECT_EQ(events[0].kind, Kind::Frames);
  EXPECT_EQ(events[0].x, 3.0f);
  EXPECT_EQ(events[1].kind, Kind::Key);
  EXPECT_EQ(events[1].name, "5");
  EXPECT_EQ(events[2].name, "shift+2");
  EXPECT_EQ(events[3].kind, Kind::Drag);
  EXPECT_EQ(events[3].name, "left");
  EXPECT_EQ(events[3].y, -4.0f);
  EXPECT_EQ(events[4].kind, Kind::Scroll);
  EXPECT_EQ(events[5].kind, Kind::Resize);
  EXPECT_EQ(events[5].x, 320.0f);
  EXPECT_EQ(events[6].kind, Kind::Screenshot);
  EXPECT_EQ(events[6].name, "a.png");
  EXPECT_EQ(events[7].kind, Kind::Quit);
}

TEST(ViewerInput, BadLinesNameFileAndLine) {
  auto errorOf = [](const std::string& text) {
    try {
      parseInputScript(text, "s.txt");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(errorOf("frames 2\nkey x\n").find("s.txt:2: unknown key 'x'"), std::string::npos);
  EXPECT_NE(errorOf("frames 0\n").find("s.txt:1:"), std::string::npos);
  EXPECT_NE(errorOf("drag middle 1 2\n").find("left or right"), std::string::npos);
  EXPECT_NE(errorOf("resize 0 10\n").find("1..16384"), std::string::npos);
  EXPECT_NE(errorOf("jump\n").find("unknown command 'jump'"), std::string::npos);
  EXPECT_NE(errorOf("quit now\n").find("unexpected 'now'"), std::string::npos);
  EXPECT_THROW(loadInputScript("/nonexistent/script.txt"), Error);
}

// The README and the banner write V, F1, Esc: a script may too.
TEST(ViewerInput, KeyNamesIgnoreCaseAndEscIsEscape) {
  const auto events = parseInputScript("key V\nkey F1\nkey Esc\nkey ESCAPE\nkey Shift+2\nkey w\n", "s.txt");
  ASSERT_EQ(events.size(), 6u);
  EXPECT_EQ(events[0].name, "v");
  EXPECT_EQ(events[1].name, "f1");
  EXPECT_EQ(events[2].name, "escape");
  EXPECT_EQ(events[3].name, "escape");
  EXPECT_EQ(events[4].name, "shift+2");
  EXPECT_EQ(events[5].name, "w");
}

TEST(ViewerInput, AnUnknownKeyListsTheValidNames) {
  std::string message;
  try {
    parseInputScript("key F9\n", "s.txt");
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("s.txt:1: unknown key 'F9'"), std::string::npos) << message;
  for (const std::string& key : knownKeyNames()) EXPECT_NE(message.find(key), std::string::npos) << key;
  EXPECT_NE(message.find("esc"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// The method keys a script may press are the method table's, plain and with shift (one list:
// cms/methods.h), and no other digit is a key.
TEST(ViewerInput, MethodKeysAreTheMethodTablesKeys) {
  const std::vector<std::string>& keys = knownKeyNames();
  auto known = [&](const std::string& k) { return std::find(keys.begin(), keys.end(), k) != keys.end(); };
  for (const MethodInfo& method : methodTable()) {
    EXPECT_TRUE(known(std::string(1, method.viewerKey))) << method.name;
    EXPECT_TRUE(known("shift+" + std::string(1, method.viewerKey))) << method.name;
  }
  for (char digit = '0'; digit <= '9'; ++digit)
    if (!methodForViewerKey(digit)) EXPECT_FALSE(known(std::string(1, digit))) << digit;
}

}  // namespace
}  // namespace mixtrace
