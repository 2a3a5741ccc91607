// The non-compact quotients' test scenes (tests/render_test.cpp against the
// universal cover, tests/kernel_test.cpp against the CPU renderer): a z loop
// Sol/<(0, 0, h)> and xy loops Sol/<γ1, γ2> (sol::Lattice::Loops), each with
// the kinds of object it allows. (Not inlined: GCC 12 then warns that the
// default light may be uninitialised, which it is not.)
#pragma once

#include <sol/sol.hpp>

namespace sol::test {

// Sol/<(0, 0, 1.3)>: a ball off the axis, a box, the z axis as a tube and a
// horizontal tube along x + y, seen from inside [0, h) looking along x + y.
[[gnu::noinline]] inline sol::Scene z_loop_scene() {
  sol::Scene s;
  s.space = sol::ZLoopSpace{1.3};
  s.camera = {{0.2, -0.1, 0.6}, {1.0, 0.9, 0.15}, {0.0, 0.0, 1.0}, 100.0};
  s.objects = {{sol::Ball{{1.1, 0.9, 0.4}, 0.35}, {0.9, 0.55, 0.3}},
               {sol::Box{{-0.5, 1.4, 1.0}, {0.2, 0.15, 0.1}}, {0.35, 0.65, 0.9}, sol::Pattern::Checker},
               {sol::make_tube(sol::TubeAxis::Z, {0.0, 0.0, 0.0}, 0.08, sol::Lattice::golden()), {0.35, 0.5, 0.95}},
               {sol::Tube{{0.0, 0.8, 0.9}, glm::normalize(glm::dvec3(1.0, 1.0, 0.0)), 0.06}, {0.9, 0.35, 0.3}}};
  s.fog_density = 1.0 / 12.0;
  s.max_distance = 8.0;
  s.max_steps = 400;
  return s;
}

// Sol/<(1.6, 0.3, 0), (-0.4, 1.4, 0)>: a ball, a box and a tube along γ1,
// seen from inside P at z = 0.1.
[[gnu::noinline]] inline sol::Scene xy_loops_scene() {
  sol::Scene s;
  s.space = sol::XYLoopsSpace{{glm::dvec2(1.6, 0.3), glm::dvec2(-0.4, 1.4)}};
  const sol::Lattice lattice = *s.lattice();
  s.camera = {{0.5, 0.6, 0.1}, {1.0, 0.4, 0.1}, {0.0, 0.0, 1.0}, 100.0};
  s.objects = {{sol::Ball{{1.0, 1.2, 0.3}, 0.3}, {0.9, 0.55, 0.3}},
               {sol::Box{{0.2, 0.3, -0.5}, {0.15, 0.2, 0.1}}, {0.35, 0.65, 0.9}, sol::Pattern::Checker},
               {sol::make_tube(sol::TubeAxis::Gamma1, {0.0, 0.7, 0.6}, 0.05, lattice), {0.35, 0.8, 0.4}}};
  s.fog_density = 1.0 / 12.0;
  s.max_distance = 6.0;
  s.max_steps = 400;
  return s;
}

}  // namespace sol::test
