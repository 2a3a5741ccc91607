// Scene files from a hostile hand: a deterministic mutation fuzzer over a
// seed corpus (tests/corpus/ and every preset's JSON). Each mutant must
// either be refused with sol::InvalidArgument (never another exception,
// never a crash, never a hang) or parse into a scene that validates and
// renders (a few rays on the CPU) with no NaN or infinite value.
//
// The run in CI is bounded (kDefaultMutants, a few seconds); a longer one:
//   SOL_FUZZ_MUTANTS=1000000 SOL_FUZZ_SEED=7 build/ci/tests/sol_tests --gtest_filter='SceneFuzz.*'
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/extremes.hpp"

namespace {

constexpr int kDefaultMutants = 2500;

std::vector<std::string> seed_corpus() {
  std::vector<std::string> seeds;
  for (const auto& entry : std::filesystem::directory_iterator(SOL_CORPUS_DIR)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    seeds.push_back(text.str());
  }
  for (const std::string& name : sol::preset_names()) seeds.push_back(sol::to_json(sol::preset_scene(name)));
  return seeds;
}

// Tokens a hostile file is made of: non-finite and extreme numbers, wrong
// types, structure, keys that switch features on.
const std::vector<std::string>& dictionary() {
  static const std::vector<std::string> words = {
      "NaN", "Infinity", "-Infinity", "1e309", "-1e309", "-0", "0", "1e-320", "4.9e-324", "1e15", "1e16", "80", "-80",
      "80.0001", "800", "-710", "1e39", "1e300", "-1", "0.45", "0.46", "2", "100000", "100001", "180", "1e-7",
      "null", "true", "false", "\"\"", "\"x\"", "[]", "{}", "[0, 0]", "[0, 0, 0]", "[1, 1, 1, 1]", "[1e308, 1e308, 0]",
      "[[[[[[[[", "]]]]", "{{{{", "}}", ",", ":", "\"", "\\", "\\u0000", std::string(1, '\0'), "\xff\xfe",
      "\"type\": \"ball\"", "\"type\": \"tube\"", "\"type\": \"plane_x\"", "\"exact\": true", "\"reach\": 3",
      "\"reach\": 11", "\"quotient\": \"golden\"", "\"cutout\": true", "\"axis\": \"gamma1\"", "\"axis\": [0, 0, 1]",
      "\"frustum\": [-1, 1, -1, 1]", "\"frustum\": [1, -1, 0, 0]", "\"pattern\": \"checker\"", "\"max_steps\": 0",
      std::string(300, 'k'), "\"" + std::string(100000, 'v') + "\""};
  return words;
}

// Numbers alone: replacing one keeps the text JSON, so the mutant reaches
// the checks of values rather than the parser's.
const std::vector<std::string>& numbers() {
  static const std::vector<std::string> words = {"-0", "0", "1e-320", "4.9e-324", "1e-7", "1e-6", "0.45", "0.46", "2",
                                                 "-1", "80", "-80", "80.0001", "180", "800", "-710", "1e15", "1e16",
                                                 "100000", "100001", "1e39", "1e300", "1e309", "-1e309", "3.5", "-3.5"};
  return words;
}

std::string mutate(std::string text, std::mt19937_64& rng) {
  auto below = [&](std::size_t n) { return n == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::vector<std::string>& words = dictionary();
  const int edits = 1 + static_cast<int>(below(3));
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = below(text.size() + 1);
    const std::size_t kind = below(16);
    if (kind < 6) {  // replace the number at or after `at` by another number (JSON stays JSON)
      const std::size_t begin = text.find_first_of("-0123456789", at);
      if (begin == std::string::npos) continue;
      const std::size_t end = text.find_first_not_of("-+.0123456789eE", begin);
      text.replace(begin, (end == std::string::npos ? text.size() : end) - begin, numbers()[below(numbers().size())]);
      continue;
    }
    if (kind < 8) {  // a key and value into an object: features switched on, wrong keys
      const std::size_t brace = text.find('{', at);
      if (brace == std::string::npos) continue;
      static const std::vector<std::string> members = {
          "\"exact\": true, ", "\"reach\": 3, ", "\"reach\": 11, ", "\"cutout\": true, ", "\"pattern\": \"checker\", ",
          "\"quotient\": \"golden\", ", "\"axis\": \"gamma2\", ", "\"frustum\": [-1, 1, -1, 1], ", "\"radius\": 0.45, ",
          "\"intensity\": 1e9, ", "\"fog_distance\": 1e-6, ", "\"max_steps\": 100000, ", "\"hit_epsilon\": 0.1, ",
          "\"color\": [1, 1, 1], ", "\"zoom\": 2, "};
      text.insert(brace + 1, members[below(members.size())]);
      continue;
    }
    switch (kind - 8) {
      case 0:  // a random byte
        if (!text.empty()) text[std::min(at, text.size() - 1)] = static_cast<char>(below(256));
        break;
      case 1:  // delete a range
        text.erase(at, below(16) + 1);
        break;
      case 2: {  // duplicate a range
        const std::string piece = text.substr(at, below(64) + 1);
        text.insert(below(text.size() + 1), piece);
        break;
      }
      case 3:  // insert a word
        text.insert(at, words[below(words.size())]);
        break;
      case 4: {  // replace the number at or after `at` by a word
        const std::size_t begin = text.find_first_of("-0123456789", at);
        if (begin == std::string::npos) break;
        const std::size_t end = text.find_first_not_of("-+.0123456789eE", begin);
        text.replace(begin, (end == std::string::npos ? text.size() : end) - begin, words[below(words.size())]);
        break;
      }
      case 5:  // truncate
        text.resize(at);
        break;
      case 6: {  // nest a value deeply
        const std::size_t depth = below(64) + 1;
        text.insert(std::min(at, text.size()), std::string(depth, '['));
        text.append(std::string(depth, ']'));
        break;
      }
      default: {  // swap two bytes
        if (text.size() > 1) std::swap(text[below(text.size())], text[below(text.size())]);
        break;
      }
    }
  }
  return text;
}

std::string shown(const std::string& text) {
  std::string s = text.substr(0, 400);
  for (char& c : s) {
    if (static_cast<unsigned char>(c) < 32 && c != '\n') c = '?';
  }
  return s + (text.size() > 400 ? "... (" + std::to_string(text.size()) + " bytes)" : "");
}

}  // namespace

TEST(SceneFuzz, MutantsAreRefusedCleanlyOrRenderFinite) {
  const std::vector<std::string> seeds = seed_corpus();
  ASSERT_GE(seeds.size(), 9u);
  // Every seed is a valid scene (else the fuzzer explores only errors).
  for (const std::string& seed : seeds) EXPECT_NO_THROW((void)sol::parse_scene(seed, "seed.json")) << seed;
  const char* count_text = std::getenv("SOL_FUZZ_MUTANTS");
  const char* seed_text = std::getenv("SOL_FUZZ_SEED");
  const int mutants = count_text ? std::atoi(count_text) : kDefaultMutants;
  std::mt19937_64 rng(seed_text ? std::strtoull(seed_text, nullptr, 10) : 1u);
  int refused = 0, accepted = 0, rendered = 0, failures = 0;
  for (int m = 0; m < mutants && failures < 5; ++m) {
    const std::string text = mutate(seeds[static_cast<std::size_t>(m) % seeds.size()], rng);
    sol::Scene scene;
    try {
      scene = sol::parse_scene(text, "fuzz.json");
    } catch (const sol::InvalidArgument& e) {
      ++refused;
      // Messages are short: values are quoted cut.
      EXPECT_LT(std::string(e.what()).size(), 1200u) << shown(text);
      continue;
    } catch (const std::exception& e) {
      ++failures;
      ADD_FAILURE() << "mutant " << m << " threw " << typeid(e).name() << ": " << e.what() << "\n" << shown(text);
      continue;
    }
    ++accepted;
    // Accepted scenes validate, and (every fourth, at most 400 steps a ray)
    // render 4x3 rays on the CPU with finite colours and AOVs.
    EXPECT_NO_THROW(sol::validate(scene)) << shown(text);
    if (m % 4 != 0) continue;
    scene.max_steps = std::min(scene.max_steps, 400);
    sol::RenderOptions settings;
    settings.width = 4;
    settings.height = 3;
    settings.threads = 1;
    try {
      const sol::RenderResult r = sol::render_cpu(scene, settings);
      ++rendered;
      EXPECT_EQ(sol::test::non_finite_values(r), 0) << shown(text);
    } catch (const std::exception& e) {
      ++failures;
      ADD_FAILURE() << "mutant " << m << " parsed but did not render: " << e.what() << "\n" << shown(text);
    }
  }
  std::printf("scene fuzz: %d mutants, %d refused, %d accepted (%d rendered)\n", refused + accepted + failures, refused,
              accepted, rendered);
  // The mutations must reach both sides (a fuzzer that only breaks syntax
  // tests little).
  EXPECT_GT(accepted, mutants / 50);
  EXPECT_GT(refused, mutants / 2);
}
