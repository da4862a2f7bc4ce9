// The README and `mixtrace --help` name the same options, so neither drifts from the other:
//   - every option `--help` mentions appears somewhere in README.md;
//   - every option in the README's usage blocks (the text between `<!-- usage -->` and
//     `<!-- /usage -->` lines) is one `--help` mentions.
// To satisfy it after adding an option: name it in the README (the usage block, or the text
// around it). The failure lists what is missing on which side.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "support/run_binary.h"

namespace mixtrace {
namespace {

using testing::runMixtrace;

// Every long option `--name` (lower case, words joined by '-') in `text`. A '-' or a word
// character before it means it is part of something else (a path, a longer dash run).
std::set<std::string> longOptionsIn(const std::string& text) {
  static const std::regex option("(^|[^A-Za-z0-9_-])(--[a-z][a-z0-9]*(-[a-z0-9]+)*)");
  std::set<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
    found.insert((*it)[2].str());
  return found;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string readme() { return readFile(std::string(MIXTRACE_SOURCE_DIR) + "/README.md"); }

std::string helpText() {
  const testing::RunResult r = runMixtrace("--help");
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  return r.stdoutText + r.stderrText;
}

// The README's usage blocks, concatenated; empty when it has none.
std::string usageBlocks(const std::string& text) {
  static const std::string open = "<!-- usage -->", close = "<!-- /usage -->";
  std::string blocks;
  for (size_t begin = text.find(open); begin != std::string::npos; begin = text.find(open, begin)) {
    begin += open.size();
    const size_t end = text.find(close, begin);
    if (end == std::string::npos) {
      ADD_FAILURE() << "README.md: a '" << open << "' without its '" << close << "'";
      break;
    }
    blocks += text.substr(begin, end - begin) + "\n";
    begin = end + close.size();
  }
  return blocks;
}

std::string join(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " ") + n;
  return out;
}

TEST(ReadmeUsage, FindsOptionsTheWayTheyAreWritten) {
  EXPECT_EQ(longOptionsIn("--spp N, [--width W --height H], --opt=value, -q, --quiet"),
            (std::set<std::string>{"--spp", "--width", "--height", "--opt", "--quiet"}));
  EXPECT_EQ(longOptionsIn("--width/--height `--float-atomics off` ---- a--b x--y"),
            (std::set<std::string>{"--width", "--height", "--float-atomics"}));
}

TEST(ReadmeUsage, EveryHelpOptionIsInTheReadme) {
  const std::set<std::string> help = longOptionsIn(helpText());
  ASSERT_GE(help.size(), 20u) << "found too few options in --help; did its format change?";
  const std::set<std::string> inReadme = longOptionsIn(readme());
  std::set<std::string> missing;
  for (const std::string& o : help)
    if (!inReadme.count(o)) missing.insert(o);
  EXPECT_TRUE(missing.empty()) << "named by mixtrace --help but nowhere in README.md: " << join(missing);
}

TEST(ReadmeUsage, EveryReadmeUsageOptionIsKnownToHelp) {
  const std::string blocks = usageBlocks(readme());
  const std::set<std::string> usage = longOptionsIn(blocks);
  ASSERT_GE(usage.size(), 10u) << "README.md needs its usage block between '<!-- usage -->' and '<!-- /usage -->'";
  const std::set<std::string> help = longOptionsIn(helpText());
  std::set<std::string> unknown;
  for (const std::string& o : usage)
    if (!help.count(o)) unknown.insert(o);
  EXPECT_TRUE(unknown.empty()) << "in README.md's usage block but unknown to mixtrace --help: " << join(unknown);
}

}  // namespace
}  // namespace mixtrace
