// The tree of bounds (sol/bounds_tree.hpp, sol/coordinate_box.hpp): the box
// bound against exact Sol distances, each kind's box against its own
// distance, the tree's search against a search of every box, and the march
// through the tree against the march through the list and a plain sphere
// tracer over every object.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/crowd.hpp"

namespace {

using sol::CoordinateBox;

// Random points of a box, its corners among them.
std::vector<glm::dvec3> points_of(const CoordinateBox& box, std::mt19937_64& random, int count) {
  std::vector<glm::dvec3> out;
  for (int c = 0; c < 8; ++c) {
    out.push_back({c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z});
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    out.push_back(box.lo + (box.hi - box.lo) * glm::dvec3(unit(random), unit(random), unit(random)));
  }
  return out;
}

TEST(BoundsTree, TheBoxBoundIsBelowTheExactDistanceToEveryPointOfTheBox) {
  // Exact Sol distances (sol::distance, the closed-form connection) from
  // points outside to points inside random boxes: never below the bound,
  // and the bound within 1e-9 of it where the nearest point lies on a face
  // along z (the slab term is then exact: the vertical segment).
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> centre(-1.5, 1.5), size(0.05, 0.8), far(-3.0, 3.0);
  int checked = 0;
  for (int b = 0; b < 24; ++b) {
    const glm::dvec3 c(centre(random), centre(random), centre(random)), h(size(random), size(random), size(random));
    const CoordinateBox box{c - h, c + h};
    const std::vector<glm::dvec3> inside = points_of(box, random, 24);
    for (int i = 0; i < 10; ++i) {
      const glm::dvec3 q(far(random), far(random), far(random));
      const double bound = sol::box_distance_lower_bound(box, q);
      if (box.contains(q)) {
        EXPECT_EQ(bound, 0.0);
        continue;
      }
      for (const glm::dvec3& p : inside) {
        EXPECT_LE(bound, sol::distance(q, p) + 1e-12) << "box " << b << " point " << i;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 3000);
  // Straight above the top face the bound is the height: exact.
  const CoordinateBox box{{-1.0, -1.0, -0.5}, {1.0, 1.0, 0.5}};
  EXPECT_NEAR(sol::box_distance_lower_bound(box, {0.3, -0.2, 1.7}), sol::distance({0.3, -0.2, 1.7}, {0.3, -0.2, 0.5}), 1e-9);
  // A box that is a point: the bound is sol::distance_lower_bound's (the
  // same projections), and it is below the distance to that point's box
  // widened by nothing but its own extent: monotone in the box.
  std::uniform_real_distribution<double> any(-2.0, 2.0);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 p(any(random), any(random), any(random)), q(any(random), any(random), any(random));
    EXPECT_NEAR(sol::box_distance_lower_bound(CoordinateBox{p, p}, q), sol::distance_lower_bound(p, q),
                1e-12 * (1.0 + sol::distance_lower_bound(p, q)));
    EXPECT_LE(sol::box_distance_lower_bound(CoordinateBox{p - 0.1, p + 0.1}, q),
              sol::box_distance_lower_bound(CoordinateBox{p, p}, q));
  }
  // The empty box is infinitely far; an infinite one holds everything.
  EXPECT_EQ(sol::box_distance_lower_bound(CoordinateBox{}, {0.0, 0.0, 0.0}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(sol::box_distance_lower_bound(CoordinateBox::everywhere(), {5.0, -7.0, 3.0}), 0.0);
}

TEST(BoundsTree, EveryKindsBoxHoldsEveryPointOfIt) {
  // Points sampled densely around each object: wherever its own distance
  // (the march's surface: the bound for solids, the exact one for exact
  // balls and planes) is <= 0, the kind's coordinate box holds the point.
  // The boxes are also no larger than needed by much: the points inside
  // reach within 10 % of each finite extent (the balls' and
  // horizontal tubes' boxes are reached, boxes' are their own) (a box twice too large would
  // fail this), but for exact balls, whose box is that of the bound's ball
  // around them.
  std::mt19937_64 random(5);
  const std::vector<sol::Shape> shapes = {
      sol::Ball{{0.3, -0.2, 0.4}, 0.6, false},
      sol::Ball{{-0.5, 0.7, -0.8}, 0.9, true},
      sol::Ball{{0.0, 0.0, 1.2}, 0.2, false},
      sol::Box{{0.2, 0.1, -0.3}, {0.4, 0.3, 0.5}},
      sol::Box{{-1.0, 0.5, 0.9}, {0.2, 0.6, 0.1}},
      sol::Tube{{0.1, 0.2, 0.3}, {1.0, 0.0, 0.0}, 0.3},
      sol::Tube{{0.1, 0.2, -0.3}, {0.0, 1.0, 0.0}, 0.25},
  };
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const CoordinateBox box = sol::shape_coordinate_box(shapes[s]);
    glm::dvec3 reach_lo(std::numeric_limits<double>::infinity()), reach_hi(-std::numeric_limits<double>::infinity());
    const glm::dvec3 anchor = box.anchor();
    // The sampling region: the box's finite extent doubled, 3 units where it is infinite.
    glm::dvec3 half(3.0);
    for (int a = 0; a < 3; ++a) {
      if (std::isfinite(box.lo[a]) && std::isfinite(box.hi[a])) half[a] = std::max(box.hi[a] - box.lo[a], 1e-3);
    }
    int inside = 0;
    // (Exact balls solve a connection per point: fewer samples.)
    const bool exact = std::holds_alternative<sol::Ball>(shapes[s]) && std::get<sol::Ball>(shapes[s]).exact;
    for (int i = 0; i < (exact ? 30000 : 200000); ++i) {
      const glm::dvec3 q = anchor + half * glm::dvec3(unit(random), unit(random), unit(random));
      if (sol::shape_distance(shapes[s], q) > 0.0) continue;
      ++inside;
      ASSERT_TRUE(box.contains(q)) << "shape " << s << " at " << q.x << ", " << q.y << ", " << q.z;
      reach_lo = glm::min(reach_lo, q);
      reach_hi = glm::max(reach_hi, q);
    }
    EXPECT_GT(inside, 100) << "shape " << s;
    for (int a = 0; a < 3 && !exact; ++a) {  // (an exact ball's box is its bound ball's, which holds it)
      if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]) || box.hi[a] == box.lo[a]) continue;
      const double width = box.hi[a] - box.lo[a];
      EXPECT_LT(reach_lo[a] - box.lo[a], 0.1 * width) << "shape " << s << " axis " << a;
      EXPECT_LT(box.hi[a] - reach_hi[a], 0.1 * width) << "shape " << s << " axis " << a;
    }
  }
  // Planes are their own box's face; vertical tubes are unbounded.
  const CoordinateBox plane = sol::shape_coordinate_box(sol::PlaneZ{0.7});
  EXPECT_TRUE(plane.contains({1e6, -1e6, 0.7}));
  EXPECT_FALSE(plane.contains({0.0, 0.0, 0.7001}));
  EXPECT_TRUE(sol::shape_coordinate_box(sol::PlaneX{-0.2}).contains({-0.2, 3e5, -40.0}));
  EXPECT_TRUE(sol::shape_coordinate_box(sol::Tube{{0.4, -0.1, 0.0}, {0.0, 0.0, 1.0}, 0.4}).contains({1e9, 1e9, 9.0}));
}

TEST(BoundsTree, TheSearchFindsTheNearestBoxOfABruteForceSearch) {
  // 3000 random boxes (some infinite in one or two directions, as planes
  // and tubes): for random points, the nearest box by the search that
  // narrows its limit to the nearest found is the nearest of all (by
  // distance bound), and every item sits in exactly one leaf.
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> centre(-5.0, 5.0), size(0.01, 0.3), unit(0.0, 1.0);
  std::vector<CoordinateBox> boxes;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 c(centre(random), centre(random), 0.3 * centre(random)), h(size(random), size(random), size(random));
    CoordinateBox b{c - h, c + h};
    if (unit(random) < 0.01) b.lo.x = -std::numeric_limits<double>::infinity();
    if (unit(random) < 0.01) b = CoordinateBox::everywhere(), b.lo.z = b.hi.z = c.z;
    boxes.push_back(b);
  }
  const sol::BoundsTree tree(boxes);
  std::vector<int> seen(boxes.size(), 0);
  for (const auto& n : tree.nodes()) {
    for (std::uint32_t i = n.first; n.count > 0 && i < n.first + n.count; ++i) ++seen[tree.items()[i]];
    if (n.count == 0) continue;
    EXPECT_LE(n.count, sol::BoundsTree::kLeafSize);
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  for (int trial = 0; trial < 300; ++trial) {
    const glm::dvec3 q(1.3 * centre(random), 1.3 * centre(random), 0.5 * centre(random));
    double best = std::numeric_limits<double>::infinity();
    for (const CoordinateBox& b : boxes) best = std::min(best, sol::box_distance_lower_bound(b, q));
    double found = std::numeric_limits<double>::infinity();
    std::size_t visited = 0;
    tree.search(q, found, [&](std::uint32_t k) {
      ++visited;
      found = std::min(found, sol::box_distance_lower_bound(boxes[k], q));
      return found;
    });
    ASSERT_EQ(found, best) << "trial " << trial;
    // A limit of 0 visits nothing; the search visits a small share.
    EXPECT_LT(visited, boxes.size() / 4) << "trial " << trial;
  }
  std::size_t none = 0;
  tree.search({0.0, 0.0, 0.0}, 0.0, [&](std::uint32_t) { return ++none, 0.0; });
  EXPECT_EQ(none, 0u);
}


TEST(CrowdMarch, TheTreesMarchSeesWhatTheListsMarchSees) {
  // The same world marched through its list, and, with tiny balls added far
  // below the floor (never seen: every ray and shadow ray stays above it),
  // through its tree of bounds: the same objects at the same distances.
  // The two marches take different steps (the list solves the crossing of
  // planes x = c, y = c; the tree marches them; each stops within
  // hit_epsilon of the surface), so a pixel's object may differ on an edge
  // and its colour and distance by what hit_epsilon moves them: at most
  // 0.5 % of pixels differ in object, colour by more than 1e-3 or distance
  // by more than 1e-3 (5 of 3072 do).
  sol::World listed = sol::test::mixed_world();
  ASSERT_LE(listed.objects.size(), sol::MarchWorld::kMostListed);
  sol::World crowd = listed;
  while (crowd.objects.size() <= sol::MarchWorld::kMostListed + 8) {
    sol::SceneObject hidden;
    hidden.shape = sol::Ball{{0.1 * static_cast<double>(crowd.objects.size()), 0.0, -9.0}, 0.05, false};
    crowd.objects.push_back(hidden);
  }
  sol::Camera camera;
  camera.position = {3.0, -0.2, 2.0};  // under the cutout, looking down on the grid
  camera.forward = {0.0, 0.0, -1.0};
  camera.up = {1.0, 0.0, 0.0};
  sol::RenderOptions options;
  options.width = 64;
  options.height = 48;
  // (The mixed world is listed as a whole, more than sol::kListedObjects.)
  sol::CpuRenderer by_list, by_tree;
  by_list.set_world(std::make_shared<const sol::MarchWorld>(listed, sol::MarchWorld::kMostListed));
  by_tree.set_world(std::make_shared<const sol::MarchWorld>(crowd, sol::MarchWorld::kMostListed));
  ASSERT_EQ(by_list.world().tree(), nullptr);
  ASSERT_NE(by_tree.world().tree(), nullptr);
  const sol::RenderResult a = by_list.render(std::span(&camera, 1), options);
  const sol::RenderResult b = by_tree.render(std::span(&camera, 1), options);
  int differ = 0, hits = 0;
  std::vector<int> kinds_seen(listed.objects.size() + 1, 0);
  for (std::size_t i = 0; i < a.object.size(); ++i) {
    ++kinds_seen[static_cast<std::size_t>(a.object[i])];
    hits += a.object[i] > 0 ? 1 : 0;
    bool same = a.object[i] == b.object[i] && std::abs(a.distance[i] - b.distance[i]) <= 1e-3;
    for (int c = 0; c < 3; ++c) same = same && std::abs(a.rgba[4 * i + c] - b.rgba[4 * i + c]) <= 1e-3f;
    differ += same ? 0 : 1;
  }
  EXPECT_LE(differ, static_cast<int>(a.object.size()) / 200) << differ << " pixels differ";
  EXPECT_GT(hits, static_cast<int>(a.object.size()) / 2);
  // The picture shows many of the objects (not only the floor).
  EXPECT_GT(std::count_if(kinds_seen.begin() + 1, kinds_seen.end(), [](int n) { return n > 0; }), 25);
}

TEST(CrowdMarch, TenThousandBallsAreHitWhereAPlainSphereTracerHitsThem) {
  // 10,000 small balls: the tree's march from a camera outside the crowd
  // and one inside it against a sphere tracer that takes, at every step,
  // the least distance over all the objects (their bounds, as drawn) and
  // nothing else: the same object, at the same arc length within 1e-3
  // (each stops within hit_epsilon = 5e-5 of the bound's surface, where
  // a ray meeting it at a grazing angle may run on for up to ~1e-3).
  sol::World world;
  world.objects = sol::test::scattered_balls(10000);
  sol::CpuRenderer renderer(world);
  const sol::MarchWorld prepared(world);
  std::mt19937_64 random(17);
  std::normal_distribution<double> normal;
  int hits = 0, balls = 0, rays = 0;
  for (const sol::Camera& camera : {sol::test::crowd_camera_outside(), sol::test::crowd_camera_inside()}) {
    for (int r = 0; r < 6; ++r) {
      const glm::dvec3 direction = glm::normalize(camera.forward + 0.35 * glm::dvec3(normal(random), normal(random), normal(random)));
      const sol::MarchHit hit = renderer.march(camera, direction);
      const sol::ClosedFormGeodesic<double> ray(direction);
      int object = 0;
      double t = 0.0;
      for (int step = 0; step < 100000 && t <= world.max_distance; ++step) {
        const glm::dvec3 q = sol::multiply(camera.position, ray.at(t).position);
        double nearest = std::numeric_limits<double>::infinity();
        int k_nearest = 0;
        for (std::size_t k = 0; k < world.objects.size(); ++k) {
          const double d = sol::shape_distance(world.objects[k].shape, q);
          if (d < nearest) nearest = d, k_nearest = static_cast<int>(k) + 1;
        }
        if (nearest < world.hit_epsilon) {
          object = k_nearest;
          break;
        }
        t += nearest;
      }
      ++rays;
      EXPECT_EQ(hit.object, object) << "ray " << r;
      if (object == 0) continue;
      ++hits;
      balls += object > 1 ? 1 : 0;
      EXPECT_NEAR(hit.distance, t, 1e-3) << "ray " << r;
      EXPECT_LT(sol::shape_distance(world.objects[static_cast<std::size_t>(hit.object - 1)].shape, hit.point), world.hit_epsilon);
    }
  }
  // (Some rays from outside pass over the crowd, some meet the floor.)
  EXPECT_GE(hits, rays / 3);
  EXPECT_GE(balls, 3);
  // Rendered whole: every pixel finite, many balls seen.
  sol::RenderOptions options;
  options.width = 32;
  options.height = 24;
  const sol::Camera camera = sol::test::crowd_camera_outside();
  const sol::RenderResult image = renderer.render(std::span(&camera, 1), options);
  EXPECT_TRUE(std::all_of(image.rgba.begin(), image.rgba.end(), [](float v) { return std::isfinite(v); }));
  std::set<float> seen(image.object.begin(), image.object.end());
  EXPECT_GT(seen.size(), 50u);
  EXPECT_EQ(image.rays_out_of_steps, 0u);
}

TEST(CrowdMarch, AQuotientHoldsAListOfObjects) {
  sol::World w;
  w.objects = sol::test::scattered_balls(sol::kQuotientObjects);  // one more: the floor
  w.space = sol::ZLoopSpace{4.0};
  EXPECT_THROW(sol::validate(w), sol::InvalidArgument);
  try {
    sol::validate(w);
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("a quotient world holds at most 64 objects"), std::string::npos) << e.what();
  }
}

}  // namespace
