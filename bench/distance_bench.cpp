// distance_bench: accuracy and time per call of sol::distance and
// sol::geodesics_between for near, far and cut-locus pairs.
//
// Pairs are end points of geodesics from the origin (then left-translated by
// a random g, so both points are generic) at a known length t below the
// period T, where the distance is t (Coiculescu–Schwartz, docs/mathematics.md):
//   near:      random directions, t in [0.2, 2]
//   mid:       random directions, t in [2, 8]
//   far:       directions with c near ±1 (long periods), t in [18, 28]
//   cut-locus: t = T (on z = 0, two minimisers) and the same point lifted by 1e-9
// The end points come from the 50-digit reference (tests/support), so the
// accuracy column is against an independent computation. Prints one table
// (set, pairs, max |distance - t|), then Google Benchmark's timings
// (arguments are Google Benchmark's, e.g. --benchmark_min_time=0.2),
// including the CPU renderer's cost per ray with exact balls and lights
// (counter us_per_ray).
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <sol/sol.hpp>

#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"

namespace {

struct Pair {
  glm::dvec3 p, q;
  double length;  // the distance, known
};

struct Set {
  std::string name;
  std::vector<Pair> pairs;
};

glm::dvec3 reference_end(const glm::dvec3& d, double t) {
  sol::test::ReferenceGeodesic<> reference(d, false, sol::test::Real50(1e-20));
  return reference.at(t).position;
}

std::vector<Set> make_sets() {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto translate = [&](const glm::dvec3& q, double t) {
    const glm::dvec3 g(4.0 * u(rng) - 2.0, 4.0 * u(rng) - 2.0, 2.0 * u(rng) - 1.0);
    return Pair{g, sol::multiply(g, q), t};
  };
  std::vector<Set> sets = {{"near", {}}, {"mid", {}}, {"far", {}}, {"cut-locus", {}}};
  for (const glm::dvec3& d : sol::test::random_directions(12, 5)) {
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    const double t_near = std::min(0.95 * period, 0.2 + 1.8 * u(rng));
    sets[0].pairs.push_back(translate(reference_end(d, t_near), t_near));
    const double t_mid = std::min(0.95 * period, 2.0 + 6.0 * u(rng));
    sets[1].pairs.push_back(translate(reference_end(d, t_mid), t_mid));
  }
  for (double c : {0.999, -0.999, 0.9999, -0.9999, 0.99995}) {
    const glm::dvec3 d = sol::test::direction_with_c(0.3 + u(rng), 0.3 + u(rng), c);
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    const double t = std::min(0.9 * period, 18.0 + 10.0 * u(rng));
    sets[2].pairs.push_back(Pair{{0, 0, 0}, reference_end(d, t), t});
  }
  for (const glm::dvec3& d : sol::test::random_directions(6, 9)) {
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    if (period > 12.0) continue;
    const glm::dvec3 q = reference_end(d, period);
    sets[3].pairs.push_back(Pair{{0, 0, 0}, glm::dvec3(q.x, q.y, 0.0), period});
    sets[3].pairs.push_back(Pair{{0, 0, 0}, glm::dvec3(q.x, q.y, 1e-9), period});  // distance within ~1e-9 of T
  }
  return sets;
}

const std::vector<Set>& sets() {
  static const std::vector<Set> s = make_sets();
  return s;
}

void bench_distance(benchmark::State& state, std::size_t set) {
  const std::vector<Pair>& pairs = sets()[set].pairs;
  std::size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(sol::distance(p.p, p.q));
  }
}

void bench_between(benchmark::State& state, std::size_t set) {
  const std::vector<Pair>& pairs = sets()[set].pairs;
  std::size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(sol::geodesics_between(p.p, p.q, p.length + 2.0));
  }
}

void bench_lower_bound(benchmark::State& state) {
  const std::vector<Pair>& pairs = sets()[0].pairs;
  std::size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(sol::distance_lower_bound(p.p, p.q));
  }
}

// Cost per ray of the CPU renderer on the preset "spheres" (5 balls, one
// point light), 32 x 24, one thread: exact balls and/or exact light against
// the bound-based ball and the coordinate-direction light.
void bench_render(benchmark::State& state, bool exact_balls, bool exact_light) {
  sol::Scene scene = sol::preset_scene("spheres");
  for (sol::SceneObject& o : scene.objects) std::get<sol::Ball>(o.shape).exact = exact_balls;
  scene.lights[0].exact = exact_light;
  sol::RenderOptions settings;
  settings.width = 32;
  settings.height = 24;
  settings.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(sol::render_cpu(scene, settings));
  state.counters["us_per_ray"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * settings.width * settings.height * 1e-6,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("%-10s %5s %14s %12s\n", "set", "pairs", "max|d - t|", "max d");
  for (const Set& s : sets()) {
    double worst = 0.0, longest = 0.0;
    for (const Pair& p : s.pairs) {
      const double d = sol::distance(p.p, p.q);
      worst = std::max(worst, std::abs(d - p.length) / std::max(1.0, p.length));
      longest = std::max(longest, d);
    }
    std::printf("%-10s %5zu %14.3g %12.3f\n", s.name.c_str(), s.pairs.size(), worst, longest);
  }
  std::fflush(stdout);
  for (std::size_t k = 0; k < sets().size(); ++k) {
    benchmark::RegisterBenchmark(("distance/" + sets()[k].name).c_str(), bench_distance, k)->Unit(benchmark::kMicrosecond);
  }
  for (std::size_t k = 0; k < sets().size(); ++k) {
    benchmark::RegisterBenchmark(("geodesics_between(d+2)/" + sets()[k].name).c_str(), bench_between, k)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("distance_lower_bound/near", bench_lower_bound)->Unit(benchmark::kMicrosecond);
  for (int k = 0; k < 4; ++k) {
    const bool balls = (k & 1) != 0, light = (k & 2) != 0;
    const std::string name = std::string("render_cpu/spheres/balls:") + (balls ? "exact" : "bound") +
                             "/light:" + (light ? "exact" : "coordinate");
    benchmark::RegisterBenchmark(name.c_str(), bench_render, balls, light)->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
