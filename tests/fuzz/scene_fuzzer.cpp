// libFuzzer target: scene files. Every input is either refused with
// sol::InvalidArgument or parses into a scene that validates and survives
// its own round trip (to_json, parsed again, gives the same JSON): anything
// else (another exception, a crash, a hang, a sanitizer report) is a
// finding. Coverage-guided, it reaches what the mutation fuzzer in
// scene_fuzz_test.cpp does not; run briefly in CI over tests/corpus/, and
// for longer by hand (docs/testing.md).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include <sol/sol.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  sol::Scene scene;
  try {
    scene = sol::parse_scene(text, "fuzz.json");
  } catch (const sol::InvalidArgument&) {
    return 0;  // refused, with a message
  }
  sol::validate(scene);  // what was accepted is a valid scene
  const std::string once = sol::to_json(scene);
  const std::string twice = sol::to_json(sol::parse_scene(once, "round-trip.json"));
  if (once != twice) std::abort();  // the written scene reads back as itself
  return 0;
}
