// field_bench: the time to build a quotient world's distance field
// (sol::QuotientField, once per world: each set_world of a quotient, each
// scene edit in solview) for the presets and a crowded quotient, counter
// `images`. Arguments are Google Benchmark's.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <sol/sol.hpp>

namespace {

sol::Scene world(int which) {
  if (which < 2) return sol::preset_scene(which == 0 ? "lattice-balls" : "lattice-pillars");
  // The torus bundle of [[3, 1], [2, 1]] with a small fibre: 148 images.
  sol::Scene crowded = sol::preset_scene("trace4-balls");
  sol::set_space(crowded, sol::MonodromySpace{{3, 1, 2, 1}, 0.12});
  return crowded;
}

void BM_QuotientField(benchmark::State& state) {
  const sol::Scene scene = world(static_cast<int>(state.range(0)));
  const std::vector<sol::MarchObject> images = sol::quotient_images(scene);
  const double step = sol::quotient_max_step(scene);
  const sol::Lattice lattice = *scene.lattice();
  for (auto _ : state) {
    sol::QuotientField field(images, step, lattice);
    benchmark::DoNotOptimize(field.words().data());
  }
  state.counters["images"] = static_cast<double>(images.size());
  state.SetLabel(state.range(0) == 0 ? "lattice-balls" : state.range(0) == 1 ? "lattice-pillars" : "crowded");
}
BENCHMARK(BM_QuotientField)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
