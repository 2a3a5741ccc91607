// flow_bench: error against run time for every geodesic method.
//
// For a fixed set of directions (random ones and the stiff ones of
// docs/mathematics.md) and arc lengths 1, 10 and 50, each method setting gets
//   - its maximum endpoint error against the 50-digit coordinate-form
//     reference (tests/support/reference_geodesic.hpp), scaled as in the
//     accuracy goals: |Δposition|_∞ / max(1, |position|_∞);
//   - its time per evaluation (Google Benchmark, one call of sol::flow).
// Results go to a CSV file (default error_vs_time.csv; --csv FILE) with the
// columns method,setting,arc_length,max_error,ns_per_eval. Other arguments
// are Google Benchmark's (e.g. --benchmark_min_time=0.1).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <sol/sol.hpp>

#include "output_file.hpp"
#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"

namespace {

using glm::dvec3;

enum class Kind { Ode, ClosedDouble, ClosedDoubleNoPrecompute, ClosedFloat, ClosedFloatNoPrecompute };

struct Setting {
  std::string method;   // e.g. "rk4"
  std::string setting;  // e.g. "h=1e-3"
  Kind kind = Kind::Ode;
  sol::FlowOptions options;
};

std::vector<Setting> settings() {
  std::vector<Setting> out;
  for (double h : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3}) {
    sol::FlowOptions o;
    o.method = sol::Method::RK4;
    o.rk4_step = h;
    char name[32];
    std::snprintf(name, sizeof name, "h=%g", h);
    out.push_back({"rk4", name, Kind::Ode, o});
  }
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    sol::FlowOptions o;
    o.method = sol::Method::DormandPrince;
    o.tolerance = tol;
    char name[32];
    std::snprintf(name, sizeof name, "tol=%g", tol);
    out.push_back({"dopri5", name, Kind::Ode, o});
  }
  // Closed form: "precomputed" evaluates a ClosedFormGeodesic built once per
  // direction (the kernel's per-ray setup); "per call" builds it every time.
  out.push_back({"closed-double", "precomputed", Kind::ClosedDouble, {}});
  out.push_back({"closed-double", "per call", Kind::ClosedDoubleNoPrecompute, {}});
  out.push_back({"closed-float", "precomputed", Kind::ClosedFloat, {}});
  out.push_back({"closed-float", "per call", Kind::ClosedFloatNoPrecompute, {}});
  return out;
}

const std::vector<double> kArcLengths = {1.0, 10.0, 50.0};

struct Case {
  dvec3 direction;
  std::vector<dvec3> reference;        // one per arc length
  sol::ClosedFormGeodesic<double> closed;
  sol::ClosedFormGeodesic<float> closed_float;
  std::vector<dvec3> reference_float;  // for the float-rounded direction the float form uses
};

std::vector<Case> make_cases() {
  std::vector<dvec3> dirs = sol::test::random_directions(12, 2024);
  const std::vector<dvec3> stiff = sol::test::stiff_directions();
  for (std::size_t i = 0; i < stiff.size(); i += 4) dirs.push_back(stiff[i]);
  std::vector<Case> cases;
  for (const dvec3& d : dirs) {
    Case c{d, {}, sol::ClosedFormGeodesic<double>(d), sol::ClosedFormGeodesic<float>(glm::vec3(d)), {}};
    sol::test::ReferenceGeodesic<> reference(d);
    sol::test::ReferenceGeodesic<> reference_float{glm::dvec3(c.closed_float.direction())};
    for (double t : kArcLengths) {
      c.reference.push_back(reference.at(t).position);
      c.reference_float.push_back(reference_float.at(t).position);
    }
    cases.push_back(c);
  }
  return cases;
}

// One evaluation of a method: the endpoint of the geodesic from the origin.
dvec3 evaluate(const Setting& s, const Case& c, double t) {
  switch (s.kind) {
    case Kind::Ode:
      return sol::flow({dvec3(0.0), c.direction}, t, s.options).position;
    case Kind::ClosedDouble:
      return c.closed.at(t).position;
    case Kind::ClosedDoubleNoPrecompute:
      return sol::flow({dvec3(0.0), c.direction}, t, sol::Method::ClosedForm).position;
    case Kind::ClosedFloat:
      return dvec3(c.closed_float.at(static_cast<float>(t)).position);
    case Kind::ClosedFloatNoPrecompute:
      return dvec3(sol::ClosedFormGeodesic<float>(glm::vec3(c.direction)).at(static_cast<float>(t)).position);
  }
  return dvec3(0.0);
}

bool is_float(const Setting& s) { return s.kind == Kind::ClosedFloat || s.kind == Kind::ClosedFloatNoPrecompute; }

// Collects each benchmark's real time per iteration (ns) by name.
class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> ns_per_iteration;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type == Run::RT_Iteration) ns_per_iteration[run.benchmark_name()] = run.GetAdjustedRealTime();
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  std::string csv_path = "error_vs_time.csv";
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csv_path = argv[++i];
    } else if (std::strcmp(argv[i], "--help") == 0) {
      std::printf("usage: flow_bench [--csv FILE] [Google Benchmark options]\n"
                  "Writes method,setting,arc_length,max_error,ns_per_eval to FILE (default error_vs_time.csv).\n");
      return 0;
    } else {
      args.push_back(argv[i]);
    }
  }
  int bench_argc = static_cast<int>(args.size());
  benchmark::Initialize(&bench_argc, args.data());

  std::fprintf(stderr, "flow_bench: computing 50-digit references...\n");
  const std::vector<Case> cases = make_cases();
  const std::vector<Setting> all = settings();

  struct Row {
    std::string name;
    const Setting* setting;
    double t;
    double max_error;
  };
  std::vector<Row> rows;
  for (const Setting& s : all) {
    for (std::size_t k = 0; k < kArcLengths.size(); ++k) {
      const double t = kArcLengths[k];
      double worst = 0;
      for (const Case& c : cases) {
        const dvec3& reference = is_float(s) ? c.reference_float[k] : c.reference[k];
        worst = std::max(worst, sol::test::scaled_error(evaluate(s, c, t), reference));
      }
      std::string setting = s.setting;
      for (char& ch : setting) ch = ch == ' ' ? '-' : ch;
      const std::string name = s.method + "/" + setting + "/t=" + std::to_string(static_cast<int>(t));
      rows.push_back({name, &s, t, worst});
      benchmark::RegisterBenchmark(name.c_str(), [&s, &cases, t](benchmark::State& state) {
        std::size_t i = 0;
        for (auto _ : state) {
          benchmark::DoNotOptimize(evaluate(s, cases[i++ % cases.size()], t));
        }
      });
    }
  }

  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  std::string csv = "method,setting,arc_length,max_error,ns_per_eval\n";
  for (const Row& r : rows) {
    const auto it = reporter.ns_per_iteration.find(r.name);
    if (it == reporter.ns_per_iteration.end()) continue;  // filtered out by --benchmark_filter
    char line[256];
    std::snprintf(line, sizeof line, "%s,%s,%g,%.3e,%.1f\n", r.setting->method.c_str(), r.setting->setting.c_str(), r.t,
                  r.max_error, it->second);
    csv += line;
  }
  try {
    sol::programs::write_text_file(csv_path, csv);  // every write checked: complete or absent
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flow_bench: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "flow_bench: wrote %s\n", csv_path.c_str());
  return 0;
}
