// sol::QuotientField, the kernels' distance field of a quotient world over
// D: it never overestimates the step the march may take, and near surfaces
// its cells name every image that can be nearest. Checked against an
// independent reference: the bounds of the images of a far wider
// enumeration (|a|, |b| <= 16, |c| <= 3 from the objects as given, not
// sol::quotient_images), at random points of D, on its faces, edges and
// corners.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <utility>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/sweep.hpp"

namespace {

using glm::dvec3;

// The bound a march step uses (balls, exact or not, by their bound).
double bound(const sol::MarchObject& m, const dvec3& q) {
  if (const auto* ball = std::get_if<sol::Ball>(&m.shape)) return sol::sdf_ball(q, ball->center, ball->radius);
  return sol::object_distance(m, q);
}

// Every image g·object with g = γ1^a γ2^b γ3^c, |a|, |b| <= 16, |c| <= 3,
// whose bound at `centre` is at most `reach` (the others cannot be within
// the cap of any sample: bounds are 1-Lipschitz).
std::vector<sol::MarchObject> wide_images(const sol::World& world, const dvec3& centre, double reach) {
  const sol::Lattice lattice = sol::Lattice::golden();
  std::vector<sol::MarchObject> out;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const sol::MarchObject base{world.objects[i].shape, i};
    const bool plane = std::holds_alternative<sol::PlaneZ>(base.shape);
    const int range = plane ? 0 : 16;
    for (int c = -3; c <= 3; ++c) {
      for (int a = -range; a <= range; ++a) {
        for (int b = -range; b <= range; ++b) {
          sol::MarchObject image = sol::relative_to(base, sol::inverse(lattice.element(a, b, c)));
          if (plane) image.shape = sol::PlaneZ{std::get<sol::PlaneZ>(base.shape).c + c * lattice.height()};
          if (bound(image, centre) <= reach) out.push_back(image);
        }
      }
    }
  }
  return out;
}

// Balls and tubes at random places near D (so that the reference's
// enumeration around them is wide enough), a plane and a vertical tube.
sol::World mixed_world(std::mt19937_64& rng) {
  const sol::Lattice lattice = sol::Lattice::golden();
  std::uniform_real_distribution<double> coord(-1.0, 2.0);
  sol::World w;
  w.space = sol::GoldenSpace{};
  for (int i = 0; i < 2; ++i) {
    const dvec3 c(coord(rng), coord(rng), coord(rng));
    w.objects.push_back({sol::Ball{c, 0.45, i == 1}});
    const dvec3 through(coord(rng), coord(rng), coord(rng));
    w.objects.push_back({sol::make_tube(i == 0 ? sol::TubeAxis::Gamma1 : sol::TubeAxis::Gamma2, through, 0.3, sol::Lattice::golden())});
  }
  w.objects.push_back({sol::PlaneZ{0.3}});
  w.objects.push_back({sol::make_tube(sol::TubeAxis::Z, sol::multiply(lattice.element(1, -2, 0), dvec3(0, 0, 0.4)), 0.2, sol::Lattice::golden())});
  return w;
}

TEST(QuotientField, NeverOverestimatesAndNamesTheNearestImages) {
  const sol::Lattice lattice = sol::Lattice::golden();
  const double h = lattice.height();
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  auto in_d = [&](double s, double r, double z) { return s * g1 + r * g2 + dvec3(0, 0, z * h * (1 - 1e-12)); };
  std::vector<dvec3> samples;
  for (int i = 0; i < sol::test::sweep_count(3000, 4); ++i) samples.push_back(in_d(unit(rng), unit(rng), unit(rng)));
  for (int i = 0; i < sol::test::sweep_count(150, 4); ++i) {
    const double s = unit(rng), r = unit(rng), z = unit(rng);
    for (const dvec3& f : {in_d(0, r, z), in_d(1, r, z), in_d(s, 0, z), in_d(s, 1, z), in_d(s, r, 0), in_d(s, r, 1),
                           in_d(0, 0, z), in_d(1, 1, z), in_d(0, r, 1), in_d(s, 1, 0)}) {
      samples.push_back(f);
    }
  }
  for (double s : {0.0, 1.0}) {
    for (double r : {0.0, 1.0}) {
      for (double z : {0.0, 1.0}) samples.push_back(in_d(s, r, z));
    }
  }
  // Every sample is within `spread` of D's centre (a horizontal then vertical
  // coordinate path), so images whose bound at the centre exceeds spread + the
  // world's longest step are never within that step of a sample.
  const dvec3 centre = in_d(0.5, 0.5, 0.5);
  double spread = 0.0;
  for (const dvec3& q : samples) {
    spread = std::max(spread, std::abs(q.x - centre.x) * std::exp(-std::min(q.z, centre.z)) +
                                  std::abs(q.y - centre.y) * std::exp(std::max(q.z, centre.z)) + std::abs(q.z - centre.z));
  }
  std::vector<sol::World> worlds = {sol::preset_scene("lattice-balls"), sol::preset_scene("lattice-pillars"), mixed_world(rng)};
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    // The presets take the long step, the crowded mixed world the short one.
    const double max_step = sol::quotient_max_step(worlds[w]);
    EXPECT_EQ(max_step, w < 2 ? sol::kQuotientMaxStep : sol::kQuotientShortStep) << "world " << w;
    const std::vector<sol::MarchObject> listed = sol::quotient_images(worlds[w], max_step);
    const sol::QuotientField field(listed, max_step, sol::Lattice::golden());
    EXPECT_EQ(field.max_step(), max_step);
    const std::vector<sol::MarchObject> reference = wide_images(worlds[w], centre, spread + max_step);
    double reach_sum = 0.0, tightest = 1e300;  // the least gap between the reach and a non-candidate's bound
    int near = 0;
    sol::QuotientField::Sample cell;
    for (const dvec3& q : samples) {
      double b = max_step;
      for (const sol::MarchObject& m : reference) b = std::min(b, bound(m, q));
      // The cell's reach never overestimates: every image of the reference
      // nearer than it is a candidate (the same image: the same bound at q).
      const std::vector<int> candidates = field.candidates(q);
      const double reach = field.reach(q);
      // The march's one lookup a step (reused across samples) says the same.
      field.sample(q, cell);
      ASSERT_EQ(cell.reach, reach);
      ASSERT_EQ(cell.candidates, candidates);
      reach_sum += reach;
      ASSERT_GT(reach, sol::QuotientField::kNear - 1e-3) << "world " << w;
      ASSERT_LE(reach, max_step) << "world " << w;
      // Every cell has candidates: far from surfaces at least its nearest image.
      ASSERT_FALSE(candidates.empty()) << "world " << w;
      std::vector<double> candidate_bounds;
      for (int c : candidates) candidate_bounds.push_back(bound(listed[static_cast<std::size_t>(c)], q));
      for (const sol::MarchObject& m : reference) {
        const double d = bound(m, q);
        const bool candidate = std::any_of(candidate_bounds.begin(), candidate_bounds.end(),
                                           [&](double c) { return std::abs(c - d) < 1e-9; });
        if (!candidate) tightest = std::min(tightest, d - reach);
        if (d >= reach) continue;
        ASSERT_TRUE(candidate) << "world " << w << " at " << q.x << ", " << q.y << ", " << q.z << ": an image at " << d
                               << " within the reach " << reach << " is no candidate";
      }
      if (b < sol::QuotientField::kNear) {
        // The cell's candidates hold the nearest image: their least bound is B.
        ++near;
        double least = 1e300;
        for (int m : field.candidates(q)) least = std::min(least, bound(listed[static_cast<std::size_t>(m)], q));
        EXPECT_NEAR(least, b, 1e-9) << "world " << w << " at " << q.x << ", " << q.y << ", " << q.z;
      }
    }
    std::printf("world %zu: %zu images, %d of %zu samples near; mean reach %.3f, a non-candidate's bound at least "
                "%.2e beyond it\n",
                w, listed.size(), near, samples.size(), reach_sum / static_cast<double>(samples.size()), tightest);
    EXPECT_GT(near, sol::test::sweep_count(100, 4));
    // Useful: the reach is, on average, well beyond kFieldNear (measured
    // mean reach: printed above).
    EXPECT_GT(reach_sum / static_cast<double>(samples.size()), sol::QuotientField::kNear + 0.05);
  }
}

}  // namespace

namespace {

// The march of the quotient with every listed image's bound at every step
// (capped at the world's longest step), written here from scratch: the slow path the
// distance field and the clearances replace. Returns (object, arc length, steps).
struct SlowHit {
  int object;
  double distance;
  int steps;
};
SlowHit slow_march(const sol::Scene& scene, const std::vector<sol::MarchObject>& images, double max_step,
                   const glm::dvec3& direction) {
  const sol::Lattice lattice = sol::Lattice::golden();
  glm::dvec3 origin = lattice.teleport(scene.camera.position).point;
  auto ray = std::make_unique<sol::ClosedFormGeodesic<double>>(direction);
  double t = 0.0, local = 0.0;
  int steps = 0;
  for (int step = 0; step < scene.max_steps; ++step) {
    steps = step + 1;
    glm::dvec3 q = sol::multiply(origin, ray->at(local).position);
    if (!lattice.contains(q)) {
      const glm::dvec3 u = ray->direction_at(local);
      origin = lattice.teleport(q).point;
      ray = std::make_unique<sol::ClosedFormGeodesic<double>>(u);
      local = 0.0;
      q = origin;
    }
    double nearest = max_step;
    int owner = -1;
    for (const sol::MarchObject& m : images) {
      const double d = sol::object_distance(m, q);
      if (d < nearest) {
        nearest = d;
        owner = static_cast<int>(m.owner);
      }
    }
    if (nearest < scene.hit_epsilon) return {owner + 1, t, steps};
    t += nearest;
    local += nearest;
    if (t > scene.max_distance) break;
  }
  return {0, std::min(t, scene.max_distance), steps};
}

// The least bound of the images along the ray for arc lengths in [a, b].
double least_along(const sol::Scene& scene, const std::vector<sol::MarchObject>& images, const glm::dvec3& direction,
                   double a, double b) {
  const sol::Lattice lattice = sol::Lattice::golden();
  const sol::ClosedFormGeodesic<double> ray(direction);
  double least = 1e300;
  for (double t = a; t <= b; t += 2e-6) {
    const glm::dvec3 q = lattice.teleport(sol::multiply(scene.camera.position, ray.at(t).position)).point;
    for (const sol::MarchObject& m : images) least = std::min(least, sol::object_distance(m, q));
  }
  return least;
}

}  // namespace

// The CPU renderer's quotient march (by the field) against the slow march
// over every image: the same object at the same arc length, but where a ray
// grazes a surface. There one march's steps land within hit_epsilon of it
// and the other's straddle it; such a ray never enters the object (the least
// bound near the earlier hit is >= 0 and < hit_epsilon), and they are rare.
TEST(QuotientField, MarchAgreesWithTheSlowMarchButAtGrazingRays) {
  std::mt19937_64 rng(5);
  for (const char* name : {"lattice-balls", "lattice-pillars"}) {
    sol::Scene scene = sol::preset_scene(name);
    // Also from an observer moved far along Γ (the same view in M).
    for (const dvec3& offset : {dvec3(0.0), sol::Lattice::golden().element(5, -3, 2)}) {
      scene.camera.position = sol::multiply(offset, sol::preset_scene(name).camera.position);
      const sol::CpuRenderer renderer(scene);
      const std::vector<sol::MarchObject>& images = renderer.world().objects();
      const int w = 96, h = 64;
      int grazes = 0;
      double worst = 0.0;
      long fast_steps = 0, slow_steps = 0;
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
          const dvec3 direction = sol::camera_ray(scene.camera, i, j, w, h);
          const sol::MarchHit fast = renderer.march(scene.camera, direction);
          const auto [object, distance, steps] = slow_march(scene, images, renderer.world().max_step(), direction);
          fast_steps += fast.steps;
          slow_steps += steps;
          if (fast.object == object && (object == 0 || std::abs(fast.distance - distance) < 1e-3)) {
            if (object != 0) worst = std::max(worst, std::abs(fast.distance - distance));
            continue;
          }
          ++grazes;
          const double first = std::min(fast.object ? fast.distance : 1e9, object ? distance : 1e9);
          const double least = least_along(scene, images, direction, first - 2e-4, first + 2e-4);
          EXPECT_GE(least, 0.0) << name << " pixel " << i << ", " << j << ": a ray that enters an object must be hit by both";
          EXPECT_LT(least, scene.hit_epsilon) << name << " pixel " << i << ", " << j;
        }
      }
      std::printf("%s: %d grazing rays of %d differ, elsewhere arc lengths within %.1e; steps %ld against %ld\n", name,
                  grazes, w * h, worst, fast_steps, slow_steps);
      EXPECT_LE(grazes, w * h / 100) << name;
      EXPECT_LT(worst, 1e-3) << name;  // both stop within hit_epsilon of the same surface
      // The clearances step past the surfaces the rays graze: fewer steps
      // than this march by the least bound of every image (measured: 0.54
      // and 0.47 of them).
      EXPECT_LT(static_cast<double>(fast_steps), 0.7 * static_cast<double>(slow_steps)) << name;
    }
  }
}

// The kernels read a cell's candidates up to the first empty slot (one
// distance per candidate rather than kFieldCandidates per step), so every
// cell's word must hold its candidates in the lowest bytes and nothing after
// the first empty slot; read here from the kernel's buffer itself.
TEST(QuotientField, CandidatesFillTheSlotsFromTheFirst) {
  namespace k = sol::kernel;
  for (const char* name : {"lattice-balls", "lattice-pillars"}) {
    const sol::Scene scene = sol::preset_scene(name);
    const std::vector<sol::MarchObject> listed = sol::quotient_images(scene);
    const sol::QuotientField field(listed, sol::quotient_max_step(scene), sol::Lattice::golden());
    const std::vector<std::uint32_t>& words = field.words();
    const std::size_t cells = static_cast<std::size_t>(k::kFieldLayers) * k::kFieldCells * k::kFieldCells;
    ASSERT_EQ(words.size(), 2 * cells);  // per cell its candidates, then its reach
    // The layout march/quotient.glsl reads (field_cell, field_candidates,
    // field_reach): cell (i, j, k) at (k kFieldCells + j) kFieldCells + i,
    // the same cell as the library's lookups at its centre.
    const sol::Lattice lattice = sol::Lattice::golden();
    const dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int> ij(0, k::kFieldCells - 1), layer(0, k::kFieldLayers - 1);
    for (int n = 0; n < 500; ++n) {
      const int i = ij(rng), j = ij(rng), l = layer(rng);
      const double s = (i + 0.5) / k::kFieldCells, r = (j + 0.5) / k::kFieldCells;
      const dvec3 q(s * g1.x + r * g2.x, s * g1.y + r * g2.y, (l + 0.5) * lattice.height() / k::kFieldLayers);
      const std::size_t c = (static_cast<std::size_t>(l) * k::kFieldCells + static_cast<std::size_t>(j)) * k::kFieldCells +
                            static_cast<std::size_t>(i);
      ASSERT_EQ(static_cast<double>(std::bit_cast<float>(words[2 * c + 1])), field.reach(q)) << name;
      std::vector<int> from_word;
      for (int slot = 0; slot < k::kFieldCandidates && words[2 * c] != k::kFieldAllImages; ++slot) {
        const std::uint32_t m = (words[2 * c] >> (8 * slot)) & 255u;
        if (m != static_cast<std::uint32_t>(k::kFieldEmpty)) from_word.push_back(static_cast<int>(m));
      }
      if (words[2 * c] != k::kFieldAllImages) {
        ASSERT_EQ(from_word, field.candidates(q)) << name;
      }
    }
    int several = 0;
    for (std::size_t cell = 0; cell < cells; ++cell) {
      const std::size_t c = 2 * cell;
      if (words[c] == k::kFieldAllImages) continue;
      int held = 0;
      bool ended = false;
      for (int s = 0; s < k::kFieldCandidates; ++s) {
        const std::uint32_t slot = (words[c] >> (8 * s)) & 255u;
        if (slot == static_cast<std::uint32_t>(k::kFieldEmpty)) {
          ended = true;
          continue;
        }
        ASSERT_FALSE(ended) << name << ": candidate after an empty slot in cell " << cell;
        ASSERT_LT(slot, listed.size()) << name;
        ++held;
      }
      several += held >= 2 ? 1 : 0;
    }
    EXPECT_GT(several, 0) << name;  // the order matters somewhere
  }
}

// A longest step outside (0, kQuotientMaxStep] would list too few images
// for the step (or none): refused by name, not a field that oversteps.
TEST(QuotientField, LongestStepOutsideItsRangeIsRefused) {
  const sol::Scene scene = sol::preset_scene("lattice-balls");
  for (const double step : {0.0, -0.5, sol::kQuotientMaxStep + 0.01, std::nan("")}) {
    EXPECT_THROW((void)sol::quotient_images(scene, step), std::invalid_argument) << step;
    EXPECT_THROW(sol::QuotientField(sol::quotient_images(scene, sol::kQuotientShortStep), step, sol::Lattice::golden()), std::invalid_argument)
        << step;
  }
  EXPECT_NO_THROW(sol::QuotientField(sol::quotient_images(scene, sol::kQuotientShortStep), sol::kQuotientShortStep, sol::Lattice::golden()));
}
