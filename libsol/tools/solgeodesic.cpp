// solgeodesic: prints Sol geodesics as tables of arc length, position and
// direction, with the first integrals of docs/mathematics.md as a check.
//
//   solgeodesic                          a few representative geodesics
//   solgeodesic --direction 1,0.5,0.2 --length 10 --samples 11 --method rk4
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <sol/sol.hpp>

#include "command_line.hpp"

namespace {

// Arc lengths solgeodesic follows: beyond |z| ~ 700 e^{±z} leaves double
// anyway; the integrators' fixed steps make 1e8 a matter of minutes.
constexpr double kLongest = 1e6, kLongestIntegrated = 1e3;

// u e^{w} without 0 · inf: u = 0 exactly (vertical and plane geodesics far
// out) gives 0, and a tiny u meets a huge e^{w} in logarithms.
double scaled(double u, double w) {
  if (u == 0.0) return 0.0;
  return std::copysign(std::exp(std::log(std::abs(u)) + w), u);
}

void print_geodesic(const sol::GeodesicState& start, double length, int samples, sol::Method method) {
  const glm::dvec3 d = glm::normalize(start.direction);
  std::printf("# geodesic from (%g, %g, %g) with direction (%.6f, %.6f, %.6f)\n", start.position.x,
              start.position.y, start.position.z, d.x, d.y, d.z);
  std::printf("# %9s %14s %14s %14s %10s %10s %10s %10s %10s %10s\n", "t", "x", "y", "z", "u1", "u2", "u3",
              "dI1", "dI2", "dI3");
  for (int i = 0; i < samples; ++i) {
    const double t = length * i / (samples - 1);
    const sol::GeodesicState s = sol::flow(start, t, method);
    // First integrals are stated for geodesics from the origin: translate back.
    const glm::dvec3 q = sol::multiply(sol::inverse(start.position), s.position);
    const glm::dvec3 u = s.direction;
    const double i1 = scaled(u.x, -q.z) - d.x;
    const double i2 = scaled(u.y, q.z) - d.y;
    const double i3 = u.z + d.x * q.x - d.y * q.y - d.z;
    std::printf("  %9.4f %14.8f %14.8f %14.8f %10.6f %10.6f %10.6f %10.1e %10.1e %10.1e\n", t, s.position.x,
                s.position.y, s.position.z, u.x, u.y, u.z, i1, i2, i3);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::optional<glm::dvec3> from;
  std::vector<glm::dvec3> directions;
  double length = 5.0;
  int samples = 6;
  std::string method_name = "auto";
  sol::cli::CommandLine cl("solgeodesic", "[options]",
                           "Prints geodesics of Thurston's Sol geometry (metric e^{-2z}dx^2 + e^{2z}dy^2 + dz^2).");
  cl.add_vec3("--from", from, "X,Y,Z", "start point (default 0,0,0)");
  cl.add_value("--direction", "A,B,C",
               "initial direction in frame components (normalised); may be given more than once; without it a "
               "few representative directions are printed",
               [&](const std::string& text) {
                 const glm::dvec3 d = cl.vec3(text, "--direction");
                 if (glm::length(d) == 0.0) cl.fail("--direction must not be zero");
                 directions.push_back(d);
               });
  cl.add_number("--length", length, "L",
                "arc length to follow (default 5; negative goes backwards; |L| <= 1e6, 1e3 with rk4 or dopri)");
  cl.add_integer("--samples", samples, 2, 1000000, "N", "rows per geodesic, 2..1000000 (default 6)");
  cl.add_choice("--method", method_name, {"auto", "rk4", "dopri", "closed"}, "the flow's method (default auto)");
  cl.set_footer(
      "Columns: t, position x y z, direction (frame components) u1 u2 u3, and the drift of\n"
      "the first integrals e^{-z}u1 - a, e^{z}u2 - b, z' + a x - b y - c (relative to the start;\n"
      "beyond |z| ~ 700 a component u1 or u2 below double's range reads 0, and the drift shows it).\n"
      "Exit status 2 for bad usage, 1 when a geodesic cannot be followed.");
  cl.parse(argc, argv);
  const sol::Method method = method_name == "rk4"      ? sol::Method::RK4
                             : method_name == "dopri"  ? sol::Method::DormandPrince
                             : method_name == "closed" ? sol::Method::ClosedForm
                                                       : sol::Method::Auto;
  if (directions.empty()) {
    const double s = 1.0 / std::sqrt(2.0);
    directions = {{1, 0, 0}, {0, 0, 1}, {s, s, 0}, {0.6, 0.0, 0.8}, {0.48, 0.6, 0.64}, {0.01, 0.3, -0.95}};
  }
  // The integrators take fixed steps: their time grows with the length.
  const bool integrated = method == sol::Method::RK4 || method == sol::Method::DormandPrince;
  const double longest = integrated ? kLongestIntegrated : kLongest;
  if (!(std::abs(length) <= longest)) {
    char limit[64];
    std::snprintf(limit, sizeof limit, "[-%g, %g]", longest, longest);
    cl.fail("--length must be in " + std::string(limit) + (integrated ? " with --method rk4 or dopri" : ""));
  }
  std::printf("# libsol %s: Sol geodesics\n\n", SOL_VERSION_STRING);
  try {
    for (const glm::dvec3& d : directions) print_geodesic({from.value_or(glm::dvec3(0.0)), d}, length, samples, method);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solgeodesic: %s\n", e.what());
    return 1;
  }
  return 0;
}
