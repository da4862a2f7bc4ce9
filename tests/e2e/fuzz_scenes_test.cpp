// A bounded fuzz test of the glTF loader (issue 11, point 11): 200 mutations of the shipped scenes
// (fixed seed), each loaded in-process. Every mutant must either load or be refused with
// mixtrace::Error: no crash, no other exception, no hang (an alarm ends the process), no
// allocation past an address-space limit; what loads is finite. A handful of the survivors is
// rendered at 8x8, 1 spp, on the CPU backend: exit 0 with finite pixels, or one error line.
#include <sys/resource.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "output/exr_io.h"
#include "gltf/gltf_loader.h"
#include "support/run_binary.h"
#include "support/shipped_scenes.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

constexpr int kMutations = 200;
constexpr int kRenderedSurvivors = 4;
constexpr uint32_t kSeed = 20261201;

std::string readBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// Numbers that are valid JSON but wrong for glTF: beyond float, beyond int, negative, tiny.
const std::vector<std::string> kHostileNumbers = {"1e39",  "-1e39", "1e300", "-1e300",     "1e-45",     "-0",
                                                  "-1",    "0",     "3e38",  "4294967296", "2147483647", "1e308",
                                                  "65535", "1e20",  "-1e20", "0.5",        "7",          "100000000"};

uint32_t readU32(const std::string& b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(b[at + size_t(i)]);
  return v;
}

void appendU32(std::string& b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b += char(uint8_t(v >> (8 * i)));
}

// Mutations of two kinds: structured ones that keep the JSON valid (a value replaced by a hostile
// number, another type or nothing), which reach the loader's own checks, and byte-level ones
// (flip, delete, duplicate, truncate), which reach the parsers and the .glb container checks.
class Mutator {
 public:
  explicit Mutator(uint32_t seed) : random_(seed) {}

  std::string mutate(const std::string& bytes, bool binary) {
    if (pick(3) == 0) return mutateBytes(bytes);
    if (!binary) return mutateJsonText(bytes);
    // .glb: mutate the JSON chunk, rebuild the container with consistent lengths.
    if (bytes.size() < 20) return mutateBytes(bytes);
    const uint32_t jsonLength = readU32(bytes, 12);
    if (20 + size_t(jsonLength) > bytes.size()) return mutateBytes(bytes);
    std::string json = mutateJsonText(bytes.substr(20, jsonLength));
    while (json.size() % 4) json += ' ';
    const std::string rest = bytes.substr(20 + jsonLength);
    std::string out = bytes.substr(0, 8);
    appendU32(out, uint32_t(12 + 8 + json.size() + rest.size()));
    appendU32(out, uint32_t(json.size()));
    appendU32(out, 0x4E4F534Au);
    return out + json + rest;
  }

 private:
  std::string mutateJsonText(const std::string& text) {
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded()) return mutateBytes(text);
    nlohmann::json flat = doc.flatten();
    std::vector<std::string> keys, sensitive;
    for (auto it = flat.begin(); it != flat.end(); ++it) {
      if (it.value().is_string() && it.value().get<std::string>().size() >= 256) continue;  // buffer data
      keys.push_back(it.key());
      if (isSensitive(it.key())) sensitive.push_back(it.key());
    }
    if (keys.empty()) return mutateBytes(text);
    // Half the time one of the values the loader converts or sizes by: a dictionary, as fuzzers
    // use, so that 200 mutations reach them rather than mostly names and accessor bounds.
    const std::vector<std::string>& from = (!sensitive.empty() && pick(2) == 0) ? sensitive : keys;
    const std::string& key = from[pick(from.size())];
    switch (pick(5)) {
      case 0: flat.erase(key); break;
      case 1: flat[key] = "x"; break;
      case 2: flat[key] = true; break;
      default: flat[key] = nlohmann::json::parse(kHostileNumbers[pick(kHostileNumbers.size())]); break;
    }
    try {
      return flat.unflatten().dump();
    } catch (const std::exception&) {
      return mutateBytes(text);  // a key that no longer unflattens
    }
  }

  static bool isSensitive(const std::string& pointer) {
    static const std::vector<std::string> kNames = {"translation", "scale",          "matrix",     "rotation",
                                                    "intensity",   "emissiveStrength", "emissiveFactor", "color",
                                                    "count",       "byteLength",     "byteOffset", "yfov"};
    for (const std::string& name : kNames) {
      if (pointer.find("/" + name) != std::string::npos) return true;
    }
    return false;
  }

  std::string mutateBytes(std::string bytes) {
    if (bytes.empty()) return bytes;
    switch (pick(4)) {
      case 0: bytes[pick(bytes.size())] = char(pick(256)); break;
      case 1: bytes.erase(pick(bytes.size()), 1 + pick(64)); break;
      case 2: {
        const size_t at = pick(bytes.size());
        bytes.insert(at, bytes.substr(at, 1 + pick(256)));
        break;
      }
      default: bytes.resize(pick(bytes.size())); break;
    }
    return bytes;
  }

  size_t pick(size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(random_); }
  std::mt19937 random_;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the loader hands the renderer must be finite wherever the renderer computes with it.
void expectFinite(const Scene& scene, const std::string& name) {
  for (const Triangle& t : scene.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(finite(t.p[k]) && finite(t.n[k])) << name;
    }
  }
  for (const MaterialGpu& m : scene.materials) ASSERT_TRUE(finite(m.emission) && finite(m.baseColor)) << name;
  for (const PunctualLight& l : scene.punctualLights) ASSERT_TRUE(finite(l.intensity) && finite(l.position)) << name;
  ASSERT_TRUE(finite(scene.camera.position)) << name;
}

class FuzzScenes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // A mutant that makes the loader allocate without bound fails here (bad_alloc) instead of
    // taking the machine; one that makes it loop forever is ended by the alarm.
    struct rlimit limit {};
    getrlimit(RLIMIT_AS, &limit);
    const rlim_t cap = rlim_t(4) << 30;
    if (limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur > cap) {
      limit.rlim_cur = cap;
      setrlimit(RLIMIT_AS, &limit);
    }
    alarm(120);
  }
  static void TearDownTestSuite() { alarm(0); }
};

}  // namespace

TEST_F(FuzzScenes, MutantsLoadOrFailCleanly) {
  const std::vector<std::string> scenes = shippedScenes();
  ASSERT_FALSE(scenes.empty());
  std::vector<std::string> originals;
  for (const std::string& scene : scenes) originals.push_back(readBytes(scene));

  const fs::path dir = scratchDir("fuzz");
  Mutator mutator(kSeed);
  int loaded = 0, refused = 0;
  std::vector<fs::path> survivors;
  for (int i = 0; i < kMutations; ++i) {
    const size_t which = size_t(i) % scenes.size();
    const bool binary = fs::path(scenes[which]).extension() == ".glb";
    std::string bytes = originals[which];
    const int rounds = 1 + i % 3;  // up to three mutations stacked
    for (int r = 0; r < rounds; ++r) bytes = mutator.mutate(bytes, binary);
    const fs::path mutant = dir / ("mutant_" + std::to_string(i) + (binary ? ".glb" : ".gltf"));
    writeFile(mutant, bytes);
    const std::string name = mutant.string() + " (from " + scenes[which] + ")";
    try {
      const Scene scene = loadGltf(mutant.string());
      expectFinite(scene, name);
      ++loaded;
      if (bytes != originals[which] && survivors.size() < size_t(kRenderedSurvivors)) {
        survivors.push_back(mutant);
        continue;  // kept for rendering
      }
    } catch (const Error& e) {
      ++refused;
      if (std::getenv("FUZZ_VERBOSE")) std::cout << "refused: " << e.what() << "\n";
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << name << ": " << message;
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << ": not a mixtrace::Error: " << e.what();
    }
    fs::remove(mutant);
  }
  std::cout << kMutations << " mutants: " << loaded << " loaded, " << refused << " refused; rendering "
            << survivors.size() << "\n";
  EXPECT_EQ(loaded + refused, kMutations);
  // Both outcomes occur, or the mutations are not exercising anything.
  EXPECT_GT(loaded, 0);
  EXPECT_GT(refused, 0);

  for (const fs::path& survivor : survivors) {
    const fs::path out = dir / (survivor.stem().string() + ".exr");
    const fs::path stats = dir / (survivor.stem().string() + ".json");
    const RunResult r = runMixtrace("render '" + survivor.string() +
                                        "' --backend cpu --width 8 --height 8 --spp 1 -q --no-png --out '" +
                                        out.string() + "' --stats '" + stats.string() + "'",
                                    "", 60);
    ASSERT_NE(r.exitCode, 124) << survivor << " hung";
    if (r.exitCode != 0) {
      EXPECT_EQ(r.stderrLines().size(), 1u) << survivor << ": " << r.stderrText;
      EXPECT_LT(r.exitCode, 128) << survivor << " crashed";
      continue;
    }
    EXPECT_EQ(nlohmann::json::parse(readText(stats))["non_finite_samples"].get<long long>(), 0) << survivor;
    const Image image = readExr(out.string());
    for (float v : image.rgb) ASSERT_TRUE(std::isfinite(v)) << survivor;
  }
  fs::remove_all(dir);
}
