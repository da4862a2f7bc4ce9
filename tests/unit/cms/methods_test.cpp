// The method table (cms/methods.h) is the one list of methods: it is consistent in itself, and
// the option parser, --help, the viewer's keys and cms set-up all follow it.
#include "cms/methods.h"

#include <gtest/gtest.h>

#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "cms/cms_setup.h"
#include "session/options.h"

namespace mixtrace {
namespace {

TEST(Methods, NamesAndViewerKeysAreUniqueAndKeysRunFromOne) {
  std::set<std::string> names;
  std::set<char> keys;
  char expectedKey = '1';
  for (const MethodInfo& m : methodTable()) {
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate method " << m.name;
    EXPECT_TRUE(keys.insert(m.viewerKey).second) << "duplicate viewer key " << m.viewerKey;
    EXPECT_EQ(m.viewerKey, expectedKey++) << m.name << ": the viewer keys are 1..N in table order";
    EXPECT_FALSE(std::string(m.summary).empty()) << m.name;
  }
  EXPECT_LE(methodTable().size(), 9u) << "the viewer has one digit key per method";
  EXPECT_EQ(viewerKeyRange(), "1-" + std::to_string(methodTable().size()));
}

TEST(Methods, DefaultAndPlainMisMethodsAreRows) {
  ASSERT_NE(findMethod(kDefaultMethod), nullptr);
  EXPECT_EQ(RenderOptions().method, kDefaultMethod);
  const MethodInfo* plain = findMethod(kPlainMisMethod);
  ASSERT_NE(plain, nullptr);
  EXPECT_FALSE(plain->clusters);
  EXPECT_EQ(plain->selection, LightSelection::Power);
  EXPECT_EQ(findMethod("no-such-method"), nullptr);
}

// What a learning method reduces to keeps its selection: cms's defaults are the light BVH, so
// cms on one cluster is pt-bvh (tests/e2e/render_cli_test.cpp renders both).
TEST(Methods, PlainMisMethodForASelectionIsTheRowThatSelectsSo) {
  for (LightSelection s : {LightSelection::Uniform, LightSelection::Power, LightSelection::Bvh}) {
    const MethodInfo* plain = plainMisMethodFor(s);
    ASSERT_NE(plain, nullptr);
    EXPECT_EQ(plain->selection, s);
    EXPECT_FALSE(plain->clusters || plain->learnSelection || plain->controlVariate) << plain->name;
  }
  EXPECT_STREQ(plainMisMethodFor(findMethod(kDefaultMethod)->selection)->name, "pt-bvh");
}

TEST(Methods, LookUpsFindTheirRow) {
  for (const MethodInfo& m : methodTable()) {
    EXPECT_EQ(findMethod(m.name), &m);
    EXPECT_EQ(methodForViewerKey(m.viewerKey), &m);
  }
  EXPECT_EQ(methodForViewerKey('0'), nullptr);
  EXPECT_EQ(methodForViewerKey(char('1' + methodTable().size())), nullptr);
}

TEST(Methods, EveryRowParsesAndIsWhatTheParserKnows) {
  std::vector<std::string> names;
  for (const MethodInfo& m : methodTable()) {
    names.emplace_back(m.name);
    const char* argv[] = {"mixtrace", "render", "--method", m.name};
    EXPECT_EQ(parseCommandLine(4, argv).render.method, m.name);
  }
  EXPECT_EQ(knownMethods(), names);
}

TEST(Methods, HelpListsEveryRowWithItsSummaryAndTheViewerKeys) {
  const std::string help = helpText();
  for (const MethodInfo& m : methodTable()) {
    const std::string name = m.name;
    const std::string line = "  " + name + std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') + m.summary + "\n";
    EXPECT_NE(help.find(line), std::string::npos) << "no --help line for " << name;
  }
  EXPECT_NE(help.find("Keys: " + viewerKeyRange() + "\n"), std::string::npos);
  EXPECT_NE(help.find("shift+" + viewerKeyRange() + " its right-hand method"), std::string::npos);
}

// The flags cms set-up takes from each row, and what they were when each place compared names.
TEST(Methods, CmsSetUpTakesEachRowsFlags) {
  struct Expected {
    const char* name;
    LightSelection selection;
    bool clusters, learnSelection, controlVariate;
  };
  const Expected expected[] = {
      {"pt-uniform", LightSelection::Uniform, false, false, false},
      {"pt-power", LightSelection::Power, false, false, false},
      {"learned", LightSelection::Bvh, true, true, false},
      {"cv", LightSelection::Uniform, true, false, true},
      {"cms", LightSelection::Bvh, true, true, true},
      {"pt-bvh", LightSelection::Bvh, false, false, false},
  };
  ASSERT_EQ(methodTable().size(), std::size(expected));
  for (const Expected& e : expected) {
    const MethodInfo* row = findMethod(e.name);
    ASSERT_NE(row, nullptr) << e.name;
    EXPECT_EQ(row->selection, e.selection) << e.name;
    const CmsMethod byName = cmsMethodFor(e.name), byRow = cmsMethodFor(*row);
    for (const CmsMethod& c : {byName, byRow}) {
      EXPECT_EQ(c.clusters, e.clusters) << e.name;
      EXPECT_EQ(c.learnSelection, e.learnSelection) << e.name;
      EXPECT_EQ(c.controlVariate, e.controlVariate) << e.name;
      // The cluster methods' defaults are their selection; the pt-* methods keep the struct's.
      EXPECT_EQ(c.defaults, e.clusters ? e.selection : CmsMethod().defaults) << e.name;
    }
  }
  const CmsMethod unknown = cmsMethodFor("no-such-method");
  EXPECT_FALSE(unknown.clusters || unknown.learnSelection || unknown.controlVariate);
}

}  // namespace
}  // namespace mixtrace
