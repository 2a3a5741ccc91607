// Observer: camera convention, moves along geodesics with transported frame,
// rotations, no drift over 10^6 moves, lattice binding.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <glm/matrix.hpp>
#include <sol/sol.hpp>

namespace {

using glm::dmat3;
using glm::dvec3;

double orthonormality_error(const sol::Observer& o) {
  const dmat3 m = glm::transpose(o.frame()) * o.frame() - dmat3(1.0);
  double r = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) r = std::max(r, std::abs(m[c][i]));
  return r;
}

double diff(const dvec3& a, const dvec3& b) {
  const dvec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

TEST(Observer, FollowsTheCameraConvention) {
  const sol::Observer o({1, 2, 3}, {0, 2, 0}, {0.3, 0, 1});
  EXPECT_EQ(o.position(), dvec3(1, 2, 3));
  EXPECT_LT(diff(o.forward(), {0, 1, 0}), 1e-15);
  // right = normalize(forward × up), up' = right × forward.
  const dvec3 right = glm::normalize(glm::cross(dvec3(0, 1, 0), dvec3(0.3, 0, 1)));
  EXPECT_LT(diff(o.right(), right), 1e-15);
  EXPECT_LT(diff(o.up(), glm::cross(right, dvec3(0, 1, 0))), 1e-15);
  EXPECT_LT(orthonormality_error(o), 1e-15);
  // right = forward × up makes the columns (right, up, forward) a left-handed triple.
  EXPECT_NEAR(glm::determinant(o.frame()), -1.0, 1e-15);
  const sol::Observer d;
  EXPECT_EQ(d.position(), dvec3(0.0));
  EXPECT_LT(diff(d.forward(), {1, 0, 0}), 1e-15);
  EXPECT_LT(diff(d.up(), {0, 0, 1}), 1e-15);
}

TEST(Observer, MovesAlongGeodesicsAndTransportsTheFrame) {
  sol::Observer o({0.5, -0.5, 0.2}, {0.3, 0.4, 0.5}, {0, 0, 1});
  const sol::Observer before = o;
  const dvec3 local(0.2, -0.1, 1.0);  // right, up, forward
  o.move(local, 2.5);
  const sol::GeodesicState start{before.position(), before.frame() * glm::normalize(local)};
  const sol::GeodesicState end = sol::flow(start, 2.5);
  EXPECT_LT(diff(o.position(), end.position), 1e-12);
  // The transported frame is Q * frame; in particular the moving direction
  // expressed in the new frame keeps its local components.
  EXPECT_LT(diff(o.frame() * glm::normalize(local), end.direction), 1e-9);
  const dmat3 q = sol::transport(start, 2.5);
  for (int c = 0; c < 3; ++c) EXPECT_LT(diff(o.frame()[c], q * before.frame()[c]), 1e-9);
}

TEST(Observer, WalkingForwardTurningAroundAndBackReturns) {
  sol::Observer o({3, -1, 0.7}, {0.6, -0.2, 0.3}, {0, 0, 1});
  const sol::Observer start = o;
  o.move({0, 0, 1}, 4.0);
  o.yaw(M_PI);
  o.move({0, 0, 1}, 4.0);
  EXPECT_LT(diff(o.position(), start.position()), 1e-9);
  EXPECT_LT(diff(o.forward(), -start.forward()), 1e-9);
  EXPECT_LT(diff(o.up(), start.up()), 1e-9);
}

TEST(Observer, Rotations) {
  sol::Observer o({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  const dvec3 f = o.forward(), r = o.right(), u = o.up();
  o.yaw(M_PI / 2);
  EXPECT_LT(diff(o.forward(), r), 1e-15);
  EXPECT_LT(diff(o.up(), u), 1e-15);
  o.yaw(-M_PI / 2);
  o.pitch(M_PI / 2);
  EXPECT_LT(diff(o.forward(), u), 1e-15);
  EXPECT_LT(diff(o.right(), r), 1e-15);
  o.pitch(-M_PI / 2);
  o.roll(M_PI / 2);
  EXPECT_LT(diff(o.up(), r), 1e-15);
  EXPECT_LT(diff(o.forward(), f), 1e-15);
}

TEST(Observer, MillionSmallMovesDoNotDrift) {
  sol::Observer o({0, 0, 0}, {0.3, 0.4, 0.5}, {0, 0, 1});
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 1000000; ++i) {
    o.move({u(rng), u(rng), u(rng)}, 1e-3);
    if (i % 1000 == 0) o.yaw(0.01 * u(rng));
    worst = std::max(worst, orthonormality_error(o));
  }
  std::printf("after 10^6 moves: worst |F^T F - I| = %.2e, position %.3f %.3f %.3f\n", worst, o.position().x,
              o.position().y, o.position().z);
  EXPECT_LT(worst, 1e-14);
  EXPECT_NEAR(glm::determinant(o.frame()), -1.0, 1e-13);  // still the same handedness
}

TEST(Observer, BoundToTheLatticeStaysInTheDomain) {
  const sol::Lattice lattice = sol::Lattice::golden();
  sol::Observer free_walker({0.4, 0.3, 0.2}, {0.3, 0.9, 0.2}, {0, 0, 1});
  sol::Observer bound = free_walker;
  bound.bind(lattice);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const dvec3 dir(u(rng), u(rng), 1.0);
    free_walker.move(dir, 0.05);
    bound.move(dir, 0.05);
    ASSERT_TRUE(lattice.contains(bound.position()));
    // Teleporting is an isometry preserving the frame: the bound walker is the free one, teleported.
    const dvec3 expected = lattice.teleport(free_walker.position()).point;
    dvec3 d = bound.position() - expected;
    const glm::dvec2 sr = lattice.lattice_coordinates(d.x, d.y);  // same point modulo a face wrap
    d -= std::round(sr.x) * lattice.generators()[0] + std::round(sr.y) * lattice.generators()[1];
    EXPECT_LT(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), 1e-8) << i;
    EXPECT_LT(diff(bound.forward(), free_walker.forward()), 1e-8);
    // The copy of D it is in: the free walker's position is copy() · position().
    EXPECT_LT(diff(sol::multiply(lattice.element(bound.copy()), bound.position()), free_walker.position()), 1e-8) << i;
  }
  EXPECT_NE(bound.copy(), sol::LatticeWord{});  // the walk left the first copy
  // Binding teleports at once; unbinding leaves the position alone.
  sol::Observer far({100, -50, 7}, {1, 0, 0}, {0, 0, 1});
  far.bind(lattice);
  EXPECT_TRUE(lattice.contains(far.position()));
  // Intermediates reach φ^14·100 ≈ 8e4 in the teleport (Lattice::teleport): 1e-8 is about 50 ulps of them.
  EXPECT_LT(diff(sol::multiply(lattice.element(far.copy()), far.position()), {100, -50, 7}), 1e-8);
  far.bind(std::nullopt);
  EXPECT_FALSE(far.lattice().has_value());
  // A long walk along z in the quotient: each height γ3 more, and the word's
  // coefficients grow as λ^c (λ = φ² ≈ 2.6), past ±2^62 after some 45
  // heights. The copy is then no longer tracked; the walk goes on in D.
  sol::Observer climber({0.1, 0.2, 0.3}, {0, 0, 1}, {1, 0, 0});
  climber.bind(lattice);
  for (int i = 0; i < 70 && climber.copy_known(); ++i) climber.move({0, 0, 1}, 1.0);
  EXPECT_FALSE(climber.copy_known());
  climber.move({0, 0, 1}, 1.0);
  EXPECT_TRUE(lattice.contains(climber.position()));
  EXPECT_TRUE(std::isfinite(climber.forward().z));
  climber.bind(lattice);
  EXPECT_TRUE(climber.copy_known());
}

// In a lattice whose γ3 turns the fibre (trace -4), every teleport by an
// odd power of γ3 turns the frame: the bound walker is the free one moved by
// the isometry of its copy's word, position and frame (the differential of
// the half-turn: E1, E2 -> -E1, -E2), after walks up and down through the
// faces z = 0 and z = h.
TEST(Observer, BoundToATurningLatticeTurnsItsFrame) {
  const sol::Lattice lattice = sol::Lattice::from_monodromy({-3, -1, -2, -1});
  ASSERT_TRUE(lattice.turns());
  sol::Observer free_walker({0.4, 0.3, 0.2}, {0.3, 0.9, 0.2}, {0, 0, 1});
  sol::Observer bound = free_walker;
  bound.bind(lattice);
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1, 1);
  int odd = 0;
  for (int i = 0; i < 300; ++i) {
    const dvec3 dir(u(rng), i < 150 ? 1.0 : -1.0, u(rng));  // mostly along up: through the faces z = 0, h
    free_walker.move(dir, 0.05);
    bound.move(dir, 0.05);
    ASSERT_TRUE(lattice.contains(bound.position()));
    const sol::LatticeWord w = bound.copy();
    const bool turned = w.c % 2 != 0;
    odd += turned;
    EXPECT_LT(diff(lattice.apply(w, bound.position()), free_walker.position()), 1e-8) << i;
    auto carried = [&](const dvec3& v) { return turned ? sol::half_turn(v) : v; };
    EXPECT_LT(diff(carried(bound.forward()), free_walker.forward()), 1e-8) << i;
    EXPECT_LT(diff(carried(bound.up()), free_walker.up()), 1e-8) << i;
  }
  EXPECT_GT(odd, 20);  // the walk spent steps in copies an odd power of γ3 away
}

TEST(Observer, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sol::Observer({nan, 0, 0}, {1, 0, 0}, {0, 0, 1}), sol::InvalidArgument);
  EXPECT_THROW(sol::Observer({0, 0, 0}, {0, 0, 0}, {0, 0, 1}), sol::InvalidArgument);
  EXPECT_THROW(sol::Observer({0, 0, 0}, {0, 0, 2}, {0, 0, 1}), sol::InvalidArgument);
  sol::Observer o;
  EXPECT_THROW(o.move({0, 0, 0}, 1.0), sol::InvalidArgument);
  EXPECT_THROW(o.move({0, 0, 1}, nan), sol::InvalidArgument);
  EXPECT_THROW(o.yaw(nan), sol::InvalidArgument);
  EXPECT_THROW(o.pitch(std::numeric_limits<double>::infinity()), sol::InvalidArgument);
  EXPECT_THROW(o.roll(nan), sol::InvalidArgument);
  sol::FlowOptions bad;
  bad.tolerance = 0;
  EXPECT_THROW(o.set_flow_options(bad), sol::InvalidArgument);
  // A failed call leaves the observer unchanged.
  EXPECT_EQ(o.position(), dvec3(0.0));
}

}  // namespace
