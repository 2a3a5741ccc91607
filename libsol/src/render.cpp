#include "sol/render.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>

#include <glm/geometric.hpp>

#include "sol/closed_form.hpp"
#include "sol/connection.hpp"
#include "sol/denoise.h"
#include "sol/spreading.hpp"
#include "sol/error.hpp"
#include "sol/surface_light.h"
#include "sol/exit_search.h"
#include "sol/group.hpp"
#include "sol/lattice.hpp"
#include "sol/lens.hpp"
#include "sol/light.hpp"
#include "sol/quotient_field.hpp"
#include "sol/shapes.hpp"
#include "row_pool.hpp"
#include "sphere_exit.hpp"
#include "warm_solves.hpp"

namespace sol {
namespace {

// How far a march goes, and whether it starts on a surface it leaves: a
// shadow ray from a hit point towards a light passes the objects within
// 2 hit_epsilon of its start (the surface it was found on) until it is
// 2 hit_epsilon away from them, as rays pass through cutout planes, so the
// surface does not shadow itself where it faces the light.
struct MarchLimits {
  double length = std::numeric_limits<double>::infinity();  ///< with the world's max_distance, the shorter
  bool leave_start = false;
  /// A scene object the march leaves out (-1: none): a path's segment from
  /// the inner wall of a convex exact ball up to its exit (the exit search), in Sol.
  int skip = -1;
};

// Planes x = c and y = c met as roots, not marched. Along a geodesic from
// the origin with initial frame components (a, b, ·) the momenta conjugate
// to x and y are conserved: x' = a e^{2z}, y' = b e^{-2z}. So x(t) and y(t)
// are monotone and each such plane is crossed once at most, at the root of
// x(t) - c (y(t) - c). The first crossing among them (all solved together,
// one closed-form position per iteration): Newton's step from the latest
// point towards the least root it predicts, kept inside the bracket [lo, hi]
// (lo past no plane, hi past some; bisection where Newton leaves it), to
// double precision. A plane within the hit epsilon of the start is hit
// there (as the march's first step), unless `skip` holds it (a shadow ray
// leaving it). The kernel's twin: plane_xy_roots in compute/shaders/march/plane_roots.glsl, which stops
// at float precision.
struct PlaneCrossing {
  bool solved = true;  ///< else (no convergence: non-finite positions far out) the planes are marched
  std::size_t k = 0;
  double t = std::numeric_limits<double>::infinity();  ///< none within the limit: infinity
  glm::dvec3 q{0.0};                                   ///< the position at t (relative to the start)
  int steps = 0;                                       ///< positions evaluated
};

PlaneCrossing first_plane_crossing(const ClosedFormGeodesic<double>& ray, const std::vector<MarchObject>& objects,
                                   std::uint64_t skip, double limit, double epsilon) {
  constexpr std::size_t kNone = ~std::size_t{0};
  const glm::dvec3 d = ray.direction();
  std::uint64_t ahead = 0;  // the planes ahead of the ray, coming nearer
  PlaneCrossing r;
  double lo = 0.0, hi = limit, t = 0.0;
  bool bracketed = false;  // some plane crossed at hi
  glm::dvec3 q(0.0);
  for (int it = 0; it < 400; ++it) {
    if (it > 0) {
      q = ray.at(t).position;
      ++r.steps;
    }
    // Settled: Newton's step to the root below 1e-12 relative (the closed
    // form's positions hold 1e-14; the root's rounding is that over the rate).
    const double tolerance = 1e-12 * std::max(1.0, t);
    const double ez = std::exp(q.z);
    bool crossed = false, unsettled = false;  // some plane past, and one past by more than the tolerance
    double ahead_root = std::numeric_limits<double>::infinity(), behind_root = ahead_root, settled_root = ahead_root;
    std::size_t settled_k = kNone, behind_k = kNone;
    for (std::size_t k = 0; k < objects.size(); ++k) {
      const auto* px = std::get_if<PlaneX>(&objects[k].shape);
      const auto* py = std::get_if<PlaneY>(&objects[k].shape);
      const std::uint64_t bit = std::uint64_t{1} << k;
      if ((!px && !py) || (skip & bit)) continue;
      const double speed = px ? d.x : d.y;
      const double gap = px ? q.x - px->c : q.y - py->c;
      const double f = speed < 0.0 ? -gap : gap;  // rises along the ray; the crossing at f = 0
      if (it == 0) {
        if (std::abs(gap) * (px ? 1.0 / ez : ez) < epsilon) {  // on it at the start: hit there
          r.k = k;
          r.t = 0.0;
          return r;
        }
        if (f < 0.0 && speed != 0.0) ahead |= bit;
      }
      if (!(ahead & bit)) continue;
      const double rate = std::abs(speed) * (px ? ez * ez : 1.0 / (ez * ez));
      const double root = t - f / rate;
      const bool settled = std::abs(f / rate) <= tolerance;
      if (settled && root < settled_root) {
        settled_root = root;
        settled_k = k;
      }
      if (f >= 0.0) {
        crossed = true;
        unsettled = unsettled || !settled;
        if (root < behind_root) {
          behind_root = root;
          behind_k = k;
        }
      } else {
        ahead_root = std::min(ahead_root, root);
      }
    }
    if (settled_k != kNone && !unsettled) {
      r.k = settled_k;
      r.t = t;
      r.q = q;
      return r;
    }
    if (ahead == 0) return r;
    if (crossed) {
      hi = t;
      bracketed = true;
      if (!(hi - lo > tolerance)) {  // the bracket closed at the tolerance: the crossing is here
        r.k = behind_k;
        r.t = t;
        r.q = q;
        return r;
      }
    } else {
      if (t >= limit) return r;  // none crossed within the limit
      lo = t;
    }
    double next = crossed ? behind_root : ahead_root;
    if (bracketed) {
      // Newton inside the bracket; bisection outside it, and from the eighth
      // iteration on every fourth (a bound on the iterations whatever Newton does).
      if (!(next > lo && next < hi) || (it >= 8 && it % 4 == 3)) next = 0.5 * (lo + hi);
      if (!(hi - lo > tolerance)) next = hi;
    } else {  // no bracket yet: at most the limit, and from the eighth iteration on the limit every fourth
      next = it >= 8 && it % 4 == 3 ? limit : std::min(next, limit);
      if (!(next > lo)) next = 0.5 * (lo + limit);
    }
    t = next;
  }
  r.solved = false;  // bisection halves the bracket every fourth iteration: only non-finite values end here
  r.t = std::numeric_limits<double>::infinity();
  return r;
}

// The marches of this thread that stopped at max_steps (MarchHit::out_of_steps):
// render_eye reads them pixel by pixel, whichever march (camera, mirror,
// path, shadow) it was.
thread_local std::uint64_t t_out_of_steps = 0;

void count_out_of_steps(MarchHit& hit) {
  hit.out_of_steps = true;
  ++t_out_of_steps;
}

// A solid seen from inside: where its distance d is negative the ray is
// inside it, and the surface is at least -d away. Every solid's distance
// is 1-Lipschitz with the solid its sublevel set {d <= 0} (the exact
// ball's is the true signed distance; the bounds are maxima of distances
// to planes and of the hyperbolic planes' distances, each 1-Lipschitz:
// docs/lighting.md), so -d inside is a step as d is outside.
struct SeenDistance {
  double d;     // |distance|: the step either side
  bool inside;  // a solid the ray is inside
};

SeenDistance seen_distance(const MarchObject& object, bool solid, const glm::dvec3& q) {
  const double d = object_distance(object, q);
  const bool inside = solid && d < 0.0;
  return {inside ? -d : d, inside};
}

// The shortest geodesic from an exact ball's centre to q: its length and
// its unit tangent at q, the sphere's normal there; none where the solve
// fails or q is the centre.
struct FromCentre {
  double length = 0.0;
  glm::dvec3 normal{0.0};
};
std::optional<FromCentre> from_centre(const Ball& ball, const glm::dvec3& q) {
  try {
    const Connection c = minimising_geodesics(ball.center, q).front();
    if (!(c.length > 0.0)) return std::nullopt;
    return FromCentre{c.length, glm::normalize(ClosedFormGeodesic<double>(glm::normalize(c.direction)).direction_at(c.length))};
  } catch (const OutOfRange&) {
    return std::nullopt;
  }
}

// An exact ball's clearance from q inside it along the unit tangent u
// (sol::exact_ball_inside_clearance). At least `inside`, the exact
// distance to the sphere (r − d) the march has, where the solve fails.
double exact_ball_inside_step(const Ball& ball, const glm::dvec3& q, const glm::dvec3& u, double inside, double eps) {
  const std::optional<FromCentre> g = from_centre(ball, q);
  if (!g) return inside;
  return std::max(inside, exact_ball_inside_clearance(ball.radius - g->length, g->length, glm::dot(g->normal, u), eps));
}

// A ray that leaves an exact ball's sphere passes it until it is 2
// hit_epsilon away (as any surface it starts on), or until it turns back
// towards the sphere: a ray that leaves the inner wall at a grazing angle
// meets it again after a chord whose depth, r(1 − cos θ) for half-angle θ,
// may never reach 2 hit_epsilon, and passing the sphere for the whole
// chord it would go through the wall. `sign` holds the sign of the rate
// d' of the distance from the centre at the first step (0 before it): the
// pass ends where the rate has the other sign.
bool turned_back(double rate, double& sign) {
  if (rate == 0.0) return false;
  if (sign == 0.0) {
    sign = rate > 0.0 ? 1.0 : -1.0;
    return false;
  }
  return rate * sign < 0.0;
}

bool exact_ball_turned_back(const Ball& ball, const glm::dvec3& q, const glm::dvec3& u, double& sign) {
  const std::optional<FromCentre> g = from_centre(ball, q);
  return turned_back(g ? glm::dot(g->normal, u) : 0.0, sign);
}

// Whether a ray passing the surface of `shape` it leaves (at distance d
// from q, `inside` the solid) stops passing it at q, the surface a hit
// candidate again: 2 hit_epsilon away, or, seen from inside, where it heads
// for a face (sol::InsideClearances::nearest_rate; an exact ball: where it
// turns back towards its sphere, `leave_sign` as exact_ball_turned_back's;
// a composite, whose hollows a ray may leave from outside at a grazing
// angle: where its distance's rate, the normal's component along u, turns;
// a plane z = c: where u_z turns, as a ray that leaves it almost level
// turns back into it, z'' = u2² − u1², before it is 2 hit_epsilon away).
// Another solid's rule holds only for a ray that started into it: one that
// leaves it through the face it starts on (leave_sign 1, leaving_sign)
// heads for that face from the start, and passes it until 2 hit_epsilon away.
bool pass_ends(const Shape& shape, double d, bool inside, const glm::dvec3& q, const glm::dvec3& u, double hit_epsilon,
               double& leave_sign) {
  if (d > 2.0 * hit_epsilon) return true;
  if (is_exact_ball(shape)) return exact_ball_turned_back(std::get<Ball>(shape), q, u, leave_sign);
  if (const Composite* c = std::get_if<Composite>(&shape)) return turned_back(glm::dot(c->normal(q), u), leave_sign);
  if (std::holds_alternative<PlaneZ>(shape)) return turned_back(u.z, leave_sign);
  return inside && leave_sign <= 0.0 && shape_inside_clearances(shape, q, u).nearest_rate < 0.0;
}

// pass_ends' leave_sign of a solid (neither an exact ball nor a composite)
// whose surface a ray from q along u starts on: 1 where q lies inside it
// and the ray heads for its nearest face (it leaves through it), else 0.
double leaving_sign(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  if (!is_solid(shape) || is_exact_ball(shape) || std::holds_alternative<Composite>(shape)) return 0.0;
  if (!(shape_distance(shape, q) < 0.0)) return 0.0;
  return shape_inside_clearances(shape, q, u).nearest_rate < 0.0 ? 1.0 : 0.0;
}

// The normal at a hit, turned to face the ray where it faces away and
// `turn` (a solid met from inside).
glm::dvec3 facing_normal(const glm::dvec3& normal, const glm::dvec3& direction, bool turn) {
  return turn && glm::dot(normal, direction) > 0.0 ? -normal : normal;
}

// One march step's nearest objects, whichever way the march visits them
// (its list, march_cover; its tree, march_crowd): the least distance and
// its object, the runner-up's distance, and the least among the hit
// candidates (the objects not being passed).
struct StepNearest {
  static constexpr double kFar = std::numeric_limits<double>::infinity();
  double nearest = kFar, second = kFar, nearest_hit = kFar;
  std::size_t nearest_k = 0, hit_k = 0;
  bool nearest_inside = false, hit_inside = false;  // the nearest (to hit) is a solid the ray is inside

  void consider(std::size_t k, double d, bool inside, bool candidate) {
    if (d < nearest) {
      second = nearest;
      nearest = d;
      nearest_k = k;
      nearest_inside = inside;
    } else {
      second = std::min(second, d);
    }
    if (candidate && d < nearest_hit) {
      nearest_hit = d;
      hit_k = k;
      hit_inside = inside;
    }
  }

  // The step from q along u: where the nearest object (`o`) is a solid, its
  // clearance along the ray (sol/clearance.hpp; longer than its bound beside
  // it) up to the runner-up's distance, seen from outside (`outside`) or
  // from inside (`inside`: its faces'; an exact ball's own solve always);
  // where it is a plane z = c, its clearance to hit_epsilon (plane_z_step:
  // a ray leaving a floor almost level would otherwise crawl by |z - c|).
  // Only the nearest's: it is what limits the step, and the kernel
  // evaluates one clearance a step.
  double step(const MarchObject& o, const glm::dvec3& q, const glm::dvec3& u, double eps, bool outside, bool inside) const {
    const Shape& shape = o.shape;
    if (outside && is_solid(shape) && !nearest_inside) {  // (the clearance is the outside's)
      return std::min(second, std::max(nearest, object_clearance(o, q, u)));
    }
    if (nearest_inside && is_exact_ball(shape) && nearest > eps) {
      return std::min(second, exact_ball_inside_step(std::get<Ball>(shape), q, u, nearest, eps));
    }
    if (nearest_inside && inside && !is_exact_ball(shape)) {  // inside a solid: its faces' clearance
      return std::min(second, std::max(nearest, shape_inside_clearances(shape, q, u).ahead));
    }
    if (const PlaneZ* plane = std::get_if<PlaneZ>(&shape)) {
      return std::min(second, std::max(nearest, plane_z_step(q, u, plane->c, eps)));  // (a cutout's gap bound may be more)
    }
    return nearest;
  }
};

// The march in Sol: `objects` relative to `origin`, so the ray starts at
// the origin of their coordinates. Solids are seen from inside as well as
// from outside.
MarchHit march_cover(const MarchWorld& prepared, const glm::dvec3& origin, const std::vector<MarchObject>& objects,
                     const glm::dvec3& direction, const MarchLimits& limits = {}) {
  const detail::WarmSolves warm;  // this ray's exact solves start from each other
  const World& world = prepared.world();
  const std::size_t n = objects.size();
  const bool heights_only = prepared.features().heights_only;
  const ClosedFormGeodesic<double> ray(direction);
  MarchHit hit;
  if (heights_only) {
    // Exact culling: z stays within [min_height, max_height] along the whole
    // geodesic, so planes z = c outside that range (by more than the hit
    // epsilon) are never reached. A ray that reaches none is a miss with 0 steps.
    const double lo = ray.min_height() - world.hit_epsilon, hi = ray.max_height() + world.hit_epsilon;
    bool reachable = false;
    for (std::size_t k = 0; k < n; ++k) {
      const double c = std::get<PlaneZ>(objects[k].shape).c;
      reachable = reachable || (c >= lo && c <= hi);
    }
    if (!reachable) return hit;
  }
  double t = 0.0;
  const double max_length = std::min(world.max_distance, limits.length);
  // Cutout planes the ray is passing through (between their discs): not hits
  // until the ray is 2 hit_epsilon away from them again; meanwhile the step
  // is at least 2 hit_epsilon, so the ray leaves the plane. The surfaces a
  // shadow ray leaves likewise.
  std::uint64_t passing = 0;
  if (limits.leave_start) {
    for (std::size_t k = 0; k < n; ++k) {
      if (static_cast<int>(k) == limits.skip) continue;
      if (object_distance(objects[k], glm::dvec3(0.0)) < 2.0 * world.hit_epsilon) passing |= std::uint64_t{1} << k;
    }
  }
  std::array<double, MarchWorld::kMostListed> leave_sign{};  // (pass_ends)
  for (std::size_t k = 0; k < n; ++k) {
    if (passing & (std::uint64_t{1} << k)) leave_sign[k] = leaving_sign(objects[k].shape, glm::dvec3(0.0), direction);
  }
  const bool full = !heights_only || prepared.features().cutout_gaps;
  // Planes x = c, y = c: their first crossing solved; the march takes the
  // other objects up to it (their distance: the arc length left to it).
  const bool planes_xy = prepared.features().planes_xy;
  PlaneCrossing crossing;
  if (planes_xy) crossing = first_plane_crossing(ray, objects, passing, max_length, world.hit_epsilon);
  const bool others = !prepared.features().planes_xy_only || !crossing.solved;
  if (!others && !(crossing.t <= max_length)) {  // nothing else to march, and no crossing
    hit.steps = crossing.steps;
    hit.distance = max_length;
    return hit;
  }
  // The nearest solid's clearance (StepNearest::step) needs full positions.
  const bool solids = prepared.features().solids && full;
  std::uint64_t solid = 0;  // which objects are solids
  for (std::size_t k = 0; k < n; ++k) {
    if (is_solid(objects[k].shape)) solid |= std::uint64_t{1} << k;
  }
  for (int step = 0; step < world.max_steps; ++step) {
    if (!others) t = crossing.t;  // nothing else to march: straight to the crossing, whose position is known
    const glm::dvec3 q = !others ? crossing.q : full ? ray.at(t).position : glm::dvec3(0.0, 0.0, ray.height_at(t));
    StepNearest s;
    for (std::size_t k = 0; k < n; ++k) {
      if (static_cast<int>(k) == limits.skip) continue;
      const std::uint64_t bit = std::uint64_t{1} << k;
      const SeenDistance seen = seen_distance(objects[k], (solid & bit) != 0, q);
      double d = seen.d;
      const bool inside = seen.inside;
      if (planes_xy && crossing.solved &&
          (std::holds_alternative<PlaneX>(objects[k].shape) || std::holds_alternative<PlaneY>(objects[k].shape))) {
        d = k == crossing.k ? std::max(crossing.t - t, 0.0) : std::numeric_limits<double>::infinity();
      }
      const SceneObject& o = world.objects[k];
      if (o.cutout && std::holds_alternative<PlaneZ>(o.shape)) {
        d = std::max(d, cutout_gap_bound(o.pattern, multiply(origin, q)));
      }
      // The surface it leaves (pass_ends).
      if ((passing & bit) &&
          pass_ends(objects[k].shape, d, inside, q, ray.direction_at(t), world.hit_epsilon, leave_sign[k])) {
        passing &= ~bit;
      }
      s.consider(k, d, inside, !(passing & bit));
    }
    const double nearest =
        s.step(objects[s.nearest_k], q, ray.direction_at(t), world.hit_epsilon, solids && others, others);
    const std::size_t hit_k = s.hit_k;
    hit.steps = crossing.steps + step + 1;
    if (s.nearest_hit < world.hit_epsilon) {
      const glm::dvec3 p = full ? q : ray.at(t).position;  // the full position, once
      const SceneObject& o = world.objects[hit_k];
      const glm::dvec3 world_point = multiply(origin, p);
      const glm::dvec2 uv = shape_pattern_uv(objects[hit_k].shape, p, world_point);
      if (o.cutout && pattern_factor(o.pattern, uv.x, uv.y) != 1.0) {
        passing |= std::uint64_t{1} << hit_k;  // between the discs: go through
        t += std::max(nearest, 2.0 * world.hit_epsilon);
        if (t > max_length) break;
        continue;
      }
      hit.object = static_cast<int>(hit_k) + 1;
      hit.distance = t;
      hit.point = world_point;
      hit.normal = shape_normal(objects[hit_k].shape, p);
      hit.pattern_uv = uv;
      hit.direction = ray.direction_at(t);
      // (In Sol an exact ball's normal faces the ray wherever it faces away.)
      const bool turn = s.hit_inside || is_exact_ball(objects[hit_k].shape);
      hit.inside = turn && glm::dot(hit.normal, hit.direction) > 0.0;
      hit.normal = facing_normal(hit.normal, hit.direction, turn);
      return hit;
    }
    t += passing ? std::max(nearest, 2.0 * world.hit_epsilon) : nearest;
    if (t > max_length) break;
  }
  hit.distance = std::min(t, max_length);
  if (!(t > max_length)) count_out_of_steps(hit);  // the steps ran out first
  return hit;
}

// The march in Sol through a world of more than its listed objects:
// march_cover's, with the objects in world coordinates (the ray's point
// left-translated by `origin`, an isometry, so distances and frame
// components are those relative to it) and each step's objects those the
// tree of bounds can put nearer than the two nearest found so far, or
// within hit_epsilon (sol::BoundsTree::search: every other object's
// distance bound exceeds that limit, so neither the step nor the hit can
// depend on it). The surfaces the ray passes are few and kept in a list,
// each evaluated at every step. Planes x = c, y = c are marched by their
// distance (no crossing solved), and positions are always full.
// How near the runner-up a node's bound may be taken for its objects
// (march_crowd): in Sol the objects seen from above or below a crowd are
// nearly equidistant (the horizontal offsets shrink by e^{∓z}), and
// opening every node whose bound is a shade below the runner-up would
// visit most of them for a step that is hardly longer.
constexpr double kCrowdCover = 0.8;

MarchHit march_crowd(const MarchWorld& prepared, const glm::dvec3& origin, const glm::dvec3& direction,
                     const MarchLimits& limits = {}) {
  const detail::WarmSolves warm;  // this ray's exact solves start from each other
  const World& world = prepared.world();
  const std::vector<MarchObject>& objects = prepared.objects();
  const BoundsTree& tree = *prepared.tree();
  const double eps = world.hit_epsilon;
  const ClosedFormGeodesic<double> ray(direction);
  MarchHit hit;
  double t = 0.0;
  const double max_length = std::min(world.max_distance, limits.length);
  struct Passed {
    std::uint32_t k;
    double leave_sign;  // (exact_ball_turned_back)
  };
  std::vector<Passed> passing;  // the surfaces it passes (march_cover's mask)
  if (limits.leave_start) {
    // (A solid's distance may be below its box's bound near its surface, where
    // the bound's gradient is short: the boxes within a generous reach.)
    const double reach = std::max(2.0 * eps, 0.01);
    tree.search(origin, reach, [&](std::uint32_t k) {
      if (static_cast<int>(objects[k].owner) == limits.skip) return reach;
      if (object_distance(objects[k], origin) < 2.0 * eps) passing.push_back({k, leaving_sign(objects[k].shape, origin, direction)});
      return reach;
    });
  }
  std::vector<std::uint32_t> passed;  // this step's passed surfaces, evaluated before the search
  for (int step = 0; step < world.max_steps; ++step) {
    const glm::dvec3 q = multiply(origin, ray.at(t).position);
    const glm::dvec3 u = ray.direction_at(t);
    StepNearest s;
    const auto distance = [&](std::uint32_t k, bool& inside) {
      const SeenDistance seen = seen_distance(objects[k], is_solid(objects[k].shape), q);
      inside = seen.inside;
      const SceneObject& o = world.objects[k];
      return o.cutout && std::holds_alternative<PlaneZ>(o.shape) ? std::max(seen.d, cutout_gap_bound(o.pattern, q)) : seen.d;
    };
    passed.clear();
    for (auto it = passing.begin(); it != passing.end();) {
      bool inside = false;
      const double d = distance(it->k, inside);
      const bool ends = pass_ends(objects[it->k].shape, d, inside, q, u, eps, it->leave_sign);
      s.consider(it->k, d, inside, ends);
      passed.push_back(it->k);
      it = ends ? passing.erase(it) : it + 1;
    }
    tree.search(
        q, std::max(s.second, eps),
        [&](std::uint32_t k) {
          if (std::find(passed.begin(), passed.end(), k) == passed.end() && static_cast<int>(objects[k].owner) != limits.skip) {
            bool inside = false;
            const double d = distance(k, inside);
            s.consider(k, d, inside, true);
          }
          return std::max(s.second, eps);
        },
        [&](double bound) {
          // A node no nearer than the nearest object, within kCrowdCover of
          // the runner-up and clear of hit_epsilon: its bound stands for
          // all it holds (the step can be that much shorter, but is safe).
          if (!(bound >= s.nearest && bound >= kCrowdCover * s.second && bound > 2.0 * eps)) return -1.0;
          s.second = std::min(s.second, bound);
          return std::max(s.second, eps);
        });
    const double nearest = s.step(objects[s.nearest_k], q, u, eps, true, true);
    const auto hit_k = static_cast<std::uint32_t>(s.hit_k);
    hit.steps = step + 1;
    if (s.nearest_hit < eps) {
      const SceneObject& o = world.objects[hit_k];
      const glm::dvec2 uv = shape_pattern_uv(objects[hit_k].shape, q, q);
      if (o.cutout && pattern_factor(o.pattern, uv.x, uv.y) != 1.0) {
        passing.push_back({hit_k, 0.0});  // between the discs: go through
        t += std::max(nearest, 2.0 * eps);
        if (t > max_length) break;
        continue;
      }
      hit.object = static_cast<int>(objects[hit_k].owner) + 1;
      hit.distance = t;
      hit.point = q;
      hit.direction = u;
      hit.pattern_uv = uv;
      const bool turn = s.hit_inside || is_exact_ball(objects[hit_k].shape);
      hit.normal = shape_normal(objects[hit_k].shape, q);
      hit.inside = turn && glm::dot(hit.normal, u) > 0.0;
      hit.normal = facing_normal(hit.normal, u, turn);
      return hit;
    }
    t += passing.empty() ? nearest : std::max(nearest, 2.0 * eps);
    if (t > max_length) break;
  }
  hit.distance = std::min(t, max_length);
  if (!(t > max_length)) count_out_of_steps(hit);
  return hit;
}

// The march in Γ\Sol: the ray lives in D. Every step starts in D (a ray
// found outside is first teleported back by an element of Γ; its direction,
// in frame components, is unchanged by the left-translation, and its
// closed-form geodesic restarts there). A step is the least clearance of
// the cell's candidate images along the ray (sol::QuotientField: every
// image whose bound can be below kFieldNear in the cell, or else the
// nearest one; each image's clearance, sol/clearance.hpp, is at least its
// bound and longer beside it) capped at the cell's reach (the other
// images' bounds exceed it at q; at most the world's longest step): it
// reaches no object, so a step may cross a face of D but never passes
// through an object. The candidate that comes within hit_epsilon is the
// object hit.
//
// Over-relaxation (camera rays): where the reach, not a candidate, limits
// the step c, the march proposes kQuotientOverRelax c instead (at most
// kQuotientMaxStep) and evaluates its end e. The ray's geodesic from q is
// free of objects up to c (the step's own bound), and back from e for the
// clearance of e's candidates along the reversed tangent, capped at e's
// reach (the same bounds, for the geodesic run backwards from e: it is a
// geodesic too). Where the two cover the proposal (c + back >= proposal)
// no object lies on it and the march moves to e; else it stays at q and
// steps c, as without over-relaxation. Two sound pieces, so a proposal
// never passes through an object; a ray that only grazes a surface (within
// hit_epsilon without crossing it) may be stepped past where the plain
// march would have stopped on it. The kernel (march_quotient in compute/shaders/march/march.glsl) marches the same
// way in float.
MarchHit march_quotient(const MarchWorld& prepared, const glm::dvec3& camera, const glm::dvec3& direction,
                        const MarchLimits& limits = {}) {
  const detail::WarmSolves warm;  // this ray's exact solves start from each other
  const World& world = prepared.world();
  const QuotientField& field = *prepared.field();
  const Lattice& lattice = *prepared.lattice();
  const std::vector<MarchObject>& images = prepared.objects();
  // The camera's point of D; where its teleport turns (a lattice of
  // negative trace), frame components turn with it.
  const Teleport start = lattice.teleport(camera);
  glm::dvec3 origin = start.point;
  auto ray = std::make_unique<ClosedFormGeodesic<double>>(start.turned ? half_turn(direction) : direction);
  MarchHit hit;
  double t = 0.0, local = 0.0;  // total arc length; arc length since the last teleport
  const double max_length = std::min(world.max_distance, limits.length);
  // The images a shadow ray leaves (as march_cover's `passing`).
  std::vector<int> passing;
  if (limits.leave_start) {
    for (int k : field.candidates(origin)) {
      if (object_distance(images[static_cast<std::size_t>(k)], origin) < 2.0 * world.hit_epsilon) passing.push_back(k);
    }
  }
  std::vector<double> leave_sign(passing.size(), 0.0);  // (pass_ends), one for each passed image
  for (std::size_t i = 0; i < passing.size(); ++i) {
    leave_sign[i] = leaving_sign(images[static_cast<std::size_t>(passing[i])].shape, origin, ray->direction());
  }
  const bool over_relax = !limits.leave_start;
  // The step from the last point the march moved to (0 before the first),
  // and the part of it that point's own bound covers (the step taken where
  // a proposal fails).
  double proposal = 0.0, covered = 0.0;
  QuotientField::Sample cell;  // q's cell: the reach and the candidates (one lookup a step)
  bool reached = false;        // max_length (else the steps ran out first)
  for (int step = 0; step < world.max_steps; ++step) {
    // The position and the tangent (frame components, kept by the teleport's
    // left translation: the restarted ray starts along it).
    const ClosedFormGeodesic<double>::State state = ray->at(local + proposal);
    glm::dvec3 q = multiply(origin, state.position);
    glm::dvec3 u = state.direction;
    const bool outside = !lattice.contains(q);
    if (outside) {
      const Teleport back = lattice.teleport(q);
      q = back.point;
      if (back.turned) u = half_turn(u);
    }
    hit.steps = step + 1;
    field.sample(q, cell);
    // The clearances ahead and (for a proposal to check) back.
    double clear = std::numeric_limits<double>::infinity(), back = clear, nearest_hit = clear;
    const bool check = proposal > covered;
    int nearest_k = -1;
    bool hit_inside = false;
    for (int k : cell.candidates) {
      const MarchObject& image = images[static_cast<std::size_t>(k)];
      const SeenDistance seen = seen_distance(image, is_solid(image.shape), q);
      const double d = seen.d;
      auto left = std::find(passing.begin(), passing.end(), k);
      if (left != passing.end()) {  // (as march_cover's)
        double& sign = leave_sign[static_cast<std::size_t>(left - passing.begin())];
        if (pass_ends(image.shape, d, seen.inside, q, u, world.hit_epsilon, sign)) {
          leave_sign.erase(leave_sign.begin() + (left - passing.begin()));
          left = passing.erase(left);
        }
      }
      if (seen.inside) {  // inside: the faces' clearances (an exact ball's ahead by its own, back by d)
        if (is_exact_ball(image.shape)) {
          clear = std::min(clear, d > world.hit_epsilon
                                      ? exact_ball_inside_step(std::get<Ball>(image.shape), q, u, d, world.hit_epsilon)
                                      : d);
          back = std::min(back, d);
        } else {
          const InsideClearances both = shape_inside_clearances(image.shape, q, u);
          clear = std::min(clear, std::max(d, both.ahead));
          back = std::min(back, std::max(d, both.back));
        }
      } else if (check) {
        const Clearances both = object_clearances(image, q, u);
        clear = std::min(clear, std::max(d, both.ahead));
        back = std::min(back, std::max(d, both.back));
      } else {
        clear = std::min(clear, std::max(d, object_clearance(image, q, u)));
      }
      if (left == passing.end() && d < nearest_hit) {
        nearest_hit = d;
        nearest_k = k;
        hit_inside = seen.inside;
      }
    }
    if (check && covered + std::min(back, cell.reach) < proposal) {
      proposal = covered;  // not covered: the plain step instead
      continue;
    }
    t += proposal;
    local += proposal;
    if (outside) {
      origin = q;
      ray = std::make_unique<ClosedFormGeodesic<double>>(u);
      local = 0.0;
    }
    if (nearest_hit < world.hit_epsilon) {
      const MarchObject& image = images[static_cast<std::size_t>(nearest_k)];
      hit.object = static_cast<int>(image.owner) + 1;
      hit.distance = t;
      hit.point = q;
      // Normals are left-invariant: evaluate relative to the segment's origin
      // (a plane then faces the side the ray comes from, as in the cover).
      hit.normal = shape_normal(shape_seen_from(image.shape, origin), multiply(inverse(origin), q));
      hit.pattern_uv = shape_pattern_uv(image.shape, q, q);  // world coordinates, the image's own
      hit.direction = u;
      hit.inside = hit_inside && glm::dot(hit.normal, hit.direction) > 0.0;
      hit.normal = facing_normal(hit.normal, hit.direction, hit_inside);
      return hit;
    }
    double step_length = std::min(clear, cell.reach);
    if (!passing.empty()) step_length = std::max(step_length, 2.0 * world.hit_epsilon);
    if (t + step_length > max_length) {
      t += step_length;
      reached = true;
      break;
    }
    covered = step_length;
    proposal = over_relax && cell.reach < clear
                   ? std::min(std::max(step_length, std::min(kernel::kQuotientOverRelax * step_length, kQuotientMaxStep)),
                              max_length - t)
                   : step_length;
  }
  hit.distance = std::min(t, max_length);
  if (!reached) count_out_of_steps(hit);
  return hit;
}

// What a render shares between its rays: the objects relative to the camera
// (Sol; the quotient's rays use the prepared images as they are).
struct CameraView {
  glm::dvec3 position;
  std::vector<MarchObject> objects;
};

CameraView view_from(const MarchWorld& world, const Camera& camera) {
  const bool listed = !world.features().quotient && !world.tree();
  return {camera.position, listed ? world.seen_from(camera.position) : std::vector<MarchObject>()};
}

MarchHit march_view(const MarchWorld& world, const CameraView& view, const glm::dvec3& direction) {
  if (world.features().quotient) return march_quotient(world, view.position, direction);
  return world.tree() ? march_crowd(world, view.position, direction)
                      : march_cover(world, view.position, view.objects, direction);
}

// The march of a ray that leaves a surface (a shadow ray, a mirror's
// reflected ray, a path's next segment): from a hit point (world
// coordinates) along `direction` (frame components there), up to `length`
// (with the world's max_distance, the shorter), passing the surface it
// starts on until it is 2 hit_epsilon away.
MarchHit march_from(const MarchWorld& prepared, const glm::dvec3& from, const glm::dvec3& direction,
                    double length = std::numeric_limits<double>::infinity(), int skip = -1) {
  const MarchLimits limits{length, true, skip};
  if (prepared.features().quotient) return march_quotient(prepared, from, direction, limits);
  return prepared.tree() ? march_crowd(prepared, from, direction, limits)
                         : march_cover(prepared, from, prepared.seen_from(from), direction, limits);
}

// Whether the geodesic from a hit point along `direction` meets an object
// within `length` (a shadow ray: it leaves the hit's surface first).
bool blocked(const MarchWorld& prepared, const glm::dvec3& from, const glm::dvec3& direction, double length) {
  return march_from(prepared, from, direction, length).object != 0;
}

// The light a hit's surface reflects diffusely, before fog: its colour and
// pattern times the ambient and the lights' (shade_hit, radiance).
glm::dvec3 diffuse_light(const MarchWorld& prepared, const MarchHit& hit);

// The fog's transmittance over a ray's arc length to its hit.
double fog_transmittance(const World& world, const MarchHit& hit) { return std::exp(-world.fog_density * hit.distance); }

glm::dvec3 shade_hit(const MarchWorld& prepared, const MarchHit& hit) {
  if (hit.object == 0) return glm::dvec3(0.0);
  const World& world = prepared.world();
  const glm::dvec3 surface = diffuse_light(prepared, hit);
  const double transmittance = fog_transmittance(world, hit);
  return world.fog_color + (surface - world.fog_color) * transmittance;
}

// The albedo of object `o` at a hit: its colour times its pattern and its texture there.
glm::dvec3 albedo_at(const SceneObject& o, const MarchHit& hit) {
  const glm::dvec3 a = o.color * pattern_factor(o.pattern, hit.pattern_uv.x, hit.pattern_uv.y);
  return o.texture ? a * texture_color(*o.texture, o.texture_cells, hit.pattern_uv) : a;
}

// What a camera ray's first hit gives the denoiser's guides: its albedo
// and what it emits towards the eye (the emission times the fog's
// transmittance over the ray, as both transports add it); 0 on a miss.
struct FirstHitGuides {
  glm::dvec3 albedo{0.0}, emission{0.0};
};
FirstHitGuides first_hit_guides(const World& world, const MarchHit& hit) {
  if (hit.object == 0) return {};
  const SceneObject& o = world.objects[static_cast<std::size_t>(hit.object - 1)];
  return {albedo_at(o, hit), o.emission * fog_transmittance(world, hit)};
}

// A path's random numbers: splitmix64 (Steele, Lea, Flood 2014) from the
// seed, the pixel and the sample, so that an image does not depend on the
// threads that rendered it.
class PathRandom {
 public:
  PathRandom(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
      : m_state(seed ^ (0x9E3779B97F4A7C15ULL * (pixel + 1)) ^ (0xD1B54A32D192ED03ULL * (sample + 1))) {}
  /// Uniform in [0, 1).
  double uniform() {
    std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t m_state;
};

// The specular lobe's direction at a hit (n: its normal facing the ray):
// a glass's refraction or reflection (one number: Fresnel's choice), a
// glossy lobe's (two), else the mirror's reflection (none); the kernel
// draws the same numbers (march/shading.glsl, march/paths.glsl).
glm::dvec3 specular_direction(const kernel::SolLobes& lobes, const MarchHit& hit, const glm::dvec3& n, PathRandom& random) {
  if (lobes.ior > 0.0) return kernel::sol_dielectric_direction(hit.direction, n, lobes.ior, hit.inside, random.uniform());
  const double xi1 = lobes.roughness > 0.0 ? random.uniform() : 0.0;
  const double xi2 = lobes.roughness > 0.0 ? random.uniform() : 0.0;
  return kernel::sol_specular_direction(hit.direction, n, lobes.roughness, xi1, xi2);
}

// The exit of a path segment from the inner wall of an exact ball of
// radius below kernel::kConvexBallRadius (docs/lighting.md, "Enclosures"):
// where the distance from the centre along the ray reaches r −
// hit_epsilon/2 heading out, solved at once (detail::sphere_exit) from the
// chord 2 r cos θ (θ the angle with the inner normal). Where that finds
// none, the kernel's exit_newton: Newton's method on the arc length, one
// exact solve a round (sol/exit_search.h's rounds); none where a solve
// fails, a trial is outside while heading in or past the march's limit, or
// after kernel::kExitRounds rounds.
struct BallExit {
  double t;
  glm::dvec3 point, outward, direction;
  int rounds;
};

std::optional<BallExit> exact_ball_exit(const Ball& ball, const glm::dvec3& from, const ClosedFormGeodesic<double>& ray,
                                        double cosine, double eps, double limit) {
  double t = std::min(2.0 * ball.radius * cosine, limit);
  // The crossing of the search's level r − hit_epsilon/2 solved at once
  // (detail::sphere_exit); the rounds where that fails.
  if (const std::optional<detail::SphereExit> x = detail::sphere_exit(ball.center, ball.radius - 0.5 * eps, from, ray, t, limit)) {
    return BallExit{x->s, multiply(from, ray.at(x->s).position), x->outward, x->direction, 1};
  }
  const detail::WarmSolves warm;  // each trial's solve from the last
  for (int round = 1; round <= kernel::kExitRounds; ++round) {
    const ClosedFormGeodesic<double>::State at = ray.at(t);
    const glm::dvec3 q = multiply(from, at.position);
    const std::optional<FromCentre> g = from_centre(ball, q);
    if (!g) return std::nullopt;
    const double excess = g->length - ball.radius, slope = glm::dot(g->normal, at.direction);
    if (kernel::sol_exit_found(excess, slope, eps)) return BallExit{t, q, g->normal, at.direction, round};
    t = kernel::sol_exit_next(t, excess, slope, ball.radius, eps);
    if (!(t > 0.0 && t <= limit)) return std::nullopt;
  }
  return std::nullopt;
}

// A path's next segment from a hit along `direction` (n: the hit's normal
// facing the ray): from the inner wall of a small exact ball, its exit
// solved first (exact_ball_exit) and the other objects marched without
// the ball up to it (met by none, the ray meets the ball there); else the
// march from the hit.
MarchHit march_segment(const MarchWorld& prepared, const MarchHit& hit, const glm::dvec3& n, const glm::dvec3& direction) {
  const World& world = prepared.world();
  const SceneObject* o = hit.object > 0 ? &world.objects[static_cast<std::size_t>(hit.object - 1)] : nullptr;
  const Ball* ball = o ? std::get_if<Ball>(&o->shape) : nullptr;
  const double cosine = glm::dot(direction, n);
  if (prepared.features().quotient || !hit.inside || !ball || !ball->exact || !(ball->radius < kernel::kConvexBallRadius) ||
      !(cosine > 0.0)) {
    return march_from(prepared, hit.point, direction);
  }
  const double limit = world.max_distance;
  const std::optional<BallExit> exit =
      exact_ball_exit(*ball, hit.point, ClosedFormGeodesic<double>(direction), cosine, world.hit_epsilon, limit);
  if (!exit) return march_from(prepared, hit.point, direction);
  MarchHit met = march_from(prepared, hit.point, direction, exit->t, hit.object - 1);
  if (met.object != 0 || met.out_of_steps) return met;
  met.object = hit.object;
  met.distance = exit->t;
  met.point = exit->point;
  met.direction = exit->direction;
  met.inside = true;
  met.normal = -exit->outward;  // facing the ray, which leaves the ball
  met.pattern_uv = shape_pattern_uv(o->shape, exit->point, exit->point);
  met.steps += exit->rounds;
  return met;
}

// The march of the ray a specular lobe sends from a hit (n: its normal
// facing the ray). A ray refracted out of a solid (glass, from inside)
// starts past the surface it crosses, 3 hit_epsilon from it along the
// normal (3 hit_epsilon / |cos θ| along its geodesic, at most 150
// hit_epsilon): a march that leaves a surface passes it, but seen from
// inside only until the ray heads for a face, which a ray leaving through
// that face always does. The kernel does the same (march/shading.glsl).
MarchHit march_specular(const MarchWorld& prepared, const MarchHit& hit, const kernel::SolLobes& lobes,
                        const glm::dvec3& n, const glm::dvec3& direction) {
  if (!(lobes.ior > 0.0 && hit.inside && glm::dot(direction, n) < 0.0)) return march_segment(prepared, hit, n, direction);
  const double skip = 3.0 * prepared.world().hit_epsilon / std::max(std::abs(glm::dot(direction, n)), 0.02);
  const ClosedFormGeodesic<double>::State s = ClosedFormGeodesic<double>(direction).at(skip);
  return march_from(prepared, multiply(hit.point, s.position), s.direction);
}

// What a ray brings back where the world has mirrors or glowing objects:
// at each hit, over the fog of its segment (each segment its own
// max_distance), the object's emission, (1 - mirror) times its diffuse
// light and mirror times what the reflected geodesic brings back (its
// tangent reflected in the surface's normal, frame components: the
// reflection is that of the tangent space at the hit, an isometry of it),
// up to max_bounces reflections (past them the mirror's share is black).
// A glossy lobe reflects in a direction drawn with `random` (the pixel's
// sample's numbers: the kernel draws the same). A world without either
// shades as shade_hit, to the bit.
glm::dvec3 radiance(const MarchWorld& prepared, const MarchHit& first, PathRandom& random) {
  if (!prepared.features().mirrors && !prepared.features().emission) return shade_hit(prepared, first);
  const World& world = prepared.world();
  glm::dvec3 color(0.0), weight(1.0);
  MarchHit hit = first;
  for (int bounce = 0; hit.object != 0; ++bounce) {
    const SceneObject& o = world.objects[static_cast<std::size_t>(hit.object - 1)];
    const double transmittance = fog_transmittance(world, hit);
    color += weight * ((1.0 - transmittance) * world.fog_color);
    // The material's lobes (sol/materials.h): its diffuse share of the
    // diffuse light, and the reflected ray's weight.
    const kernel::SolLobes lobes = material_lobes(o, albedo_at(o, hit));
    const glm::dvec3 diffuse = lobes.diffuse > 0.0 ? lobes.diffuse * diffuse_light(prepared, hit) : glm::dvec3(0.0);
    color += weight * transmittance * (o.emission + diffuse);
    if (lobes.specular == glm::dvec3(0.0) || bounce == world.mirror_bounces()) break;
    weight *= transmittance * lobes.specular;
    const glm::dvec3 n = glm::dot(hit.normal, hit.direction) > 0.0 ? -hit.normal : hit.normal;
    hit = march_specular(prepared, hit, lobes, n, specular_direction(lobes, hit, n, random));
  }
  return color;
}

// The light the lights bring to a hit (sol::lights_at, with shadows), the
// cosine taken with `normal`: before the surface's colour and the ambient.
glm::dvec3 light_received(const MarchWorld& prepared, const MarchHit& hit, const glm::dvec3& normal) {
  const World& world = prepared.world();
  const glm::dvec3& p = hit.point;
  glm::dvec3 light(0.0);
  for (std::size_t i = 0; i < world.lights.size(); ++i) {
    const Light& l = world.lights[i];
    // In the quotient: along the geodesics to each of the light's images.
    const std::vector<LightAtPoint> ways =
        prepared.features().quotient ? lights_at(l, p, prepared.light_images()[i]) : lights_at(l, p);
    for (const LightAtPoint& at : ways) {
      const double cosine = glm::dot(normal, at.direction);
      if (cosine <= 0.0) continue;
      // Shadows: the geodesic the light arrives along, marched to the light.
      if (l.shadows && std::isfinite(at.length) && blocked(prepared, p, at.direction, at.length)) continue;
      light += l.color * (l.intensity * at.attenuation * cosine);
    }
  }
  return light;
}

glm::dvec3 diffuse_light(const MarchWorld& prepared, const MarchHit& hit) {
  const World& world = prepared.world();
  const SceneObject& o = world.objects[static_cast<std::size_t>(hit.object - 1)];
  const glm::dvec3 light = light_received(prepared, hit, hit.normal);
  return albedo_at(o, hit) * (world.ambient + (1.0 - world.ambient) * light);
}

// ---- Path tracing (RenderOptions::transport = Transport::Path)

// A direction about the unit normal n with density cos θ / π
// (sol_cosine_direction, shared with the kernel), from the path's next two numbers.
glm::dvec3 cosine_direction(const glm::dvec3& n, PathRandom& random) {
  const double xi1 = random.uniform(), xi2 = random.uniform();
  return kernel::sol_cosine_direction(n, xi1, xi2);
}

// Next-event estimation to glowing objects. A glowing exact
// ball's sphere S = exp_c(r S²) is sampled by a direction w at its centre,
// uniform on S², whose point y = exp_c(r w) has the area density
// 1 / (4π J_c(w, r)), J the spreading of the geodesics from c
// (sol::sphere_area_density); a glowing box's surface uniformly by area, a
// bound ball's and a tube's with a density in closed form
// (sol/surface_light.h; a tube's over a window about the foot of the
// diffuse point on its axis, which the density depends on). y is connected to the diffuse
// point x by its minimising geodesics, or with the ball's glow_reach by
// every geodesic up to their distance plus that reach, each a direction d
// at x and a length L, and each is one way light comes (next-event
// estimation picks it with the density below; a longer one is left to
// reflection sampling, whose weight there is 1): its geometric term is
// cos θ_x cos θ_y / J_x(d, L) (J_x the spreading seen from x, equal to that
// seen from y: reciprocity), where plain space has 1 / |x - y|². A
// connection counts where the march from x along d first meets that
// object at arc length L. The density of d in solid angle at x is then
// p_pick p_area J_x / cos θ_y, which weighs both strategies (the balance
// heuristic) when they are combined.
//
// The targets: in Sol the glowing objects; in a quotient each one's images
// around D (MarchWorld::objects), in the cover, whose points x of D join
// by geodesics of the cover. One is picked with a probability that
// depends on x alone (glow_pick_weight: about its solid angle), so that
// the density of any direction can be evaluated again at a later hit. A
// geodesic to an image no target lists is reflection sampling's alone.
struct GlowTarget {
  std::size_t object;          // the scene object
  // In world coordinates (the quotient: one image of it, in the cover).
  std::variant<Ball, Box, Tube> shape;
  double reach = 0.0;          // SceneObject::glow_reach: the connections up to the distance plus this

  const Ball* ball() const { return std::get_if<Ball>(&shape); }
  const Box* box() const { return std::get_if<Box>(&shape); }
  const Tube* tube() const { return std::get_if<Tube>(&shape); }
  // Whether its area density is known in closed form (every kind's but an exact ball's, which is solved).
  bool closed_form() const { return !ball() || !ball()->exact; }
  // A tube's coordinate axis (sol/surface_light.h: 0 x, 1 y, 2 z), drawn
  // over a window about the foot of the diffuse point on it.
  int axis() const { return kernel::sol_tube_light_axis(tube()->vertical(), tube()->direction.x, tube()->direction.y); }
  // The frame next-event estimation from x draws in: a ball's or box's
  // centre, or the foot of x on a tube's axis.
  glm::dvec3 centre(const glm::dvec3& x) const {
    if (const Box* b = box()) return b->center;
    if (const Ball* b = ball()) return b->center;
    return kernel::sol_tube_light_foot(axis(), tube()->through, x);
  }
  // A tube's distance bound from x, which sets the window next-event
  // estimation draws its points over (sol_light_window); 0 for the others.
  double distance_from(const glm::dvec3& x) const { return tube() ? std::abs(bound(multiply(inverse(centre(x)), x))) : 0.0; }
  // The size it is picked by from x: a ball's radius, a box's
  // sol_box_light_radius, a tube's √(r W).
  double size(const glm::dvec3& x) const {
    if (const Box* b = box()) return kernel::sol_box_light_radius(b->half_size);
    if (const Ball* b = ball()) return b->radius;
    return std::sqrt(tube()->radius * kernel::sol_light_window(distance_from(x)));
  }
  // A closed_form target's surface in its own frame w = centre(x)⁻¹·q
  // (sol/surface_light.h): the point three numbers draw (a tube's for a
  // diffuse point at distance h), the outward normal, the density per unit
  // area and the bound there.
  glm::dvec3 point(double u0, double u1, double u2, double h) const {
    if (const Box* b = box()) return kernel::sol_box_light_point(b->half_size, u0, u1, u2);
    if (const Ball* b = ball()) return kernel::sol_ball_light_point(b->radius, u0, u1, u2);
    return kernel::sol_tube_light_point(axis(), tube()->radius, h, u0, u1, u2);
  }
  glm::dvec3 normal(const glm::dvec3& w) const {
    if (const Box* b = box()) return kernel::sol_box_light_normal(w, b->half_size);
    if (ball()) return kernel::sol_ball_light_normal(w);
    return kernel::sol_tube_light_normal(axis(), w, tube()->radius);
  }
  // The density at w (a tube's for a diffuse point at distance h: 0 outside its window).
  double density(const glm::dvec3& w, double h) const {
    if (const Box* b = box()) return 1.0 / kernel::sol_box_light_area(b->half_size);
    if (const Ball* b = ball()) return kernel::sol_ball_light_density(w, b->radius);
    return kernel::sol_tube_light_density(axis(), w, tube()->radius, h);
  }
  double bound(const glm::dvec3& w) const {
    if (const Box* b = box()) return kernel::sol_box_light_bound(w, b->half_size);
    if (const Ball* b = ball()) return kernel::sol_ball_light_bound(w, b->radius);
    return kernel::sol_tube_light_bound(axis(), w, tube()->radius);
  }
  // A light point wy on the face of a box or tube that holds wx:
  // reflection sampling's alone (sol_box_light_same_face, sol_tube_light_same_face).
  bool skips(const glm::dvec3& wx, const glm::dvec3& wy) const {
    if (const Box* b = box()) return kernel::sol_box_light_same_face(wx, wy, b->half_size);
    return tube() && kernel::sol_tube_light_same_face(axis(), wx, wy, tube()->radius);
  }
};

// The targets: sol::glow_target_objects' (a glowing plane is found by
// reflection: drawn over a window, it cost more than it saved; in a
// quotient every image around D is a target, and next-event estimation to
// other kinds than exact balls cost more than it saved: docs/lighting.md),
// each of its MarchObjects (the quotient: its images).
std::vector<GlowTarget> glow_targets(const MarchWorld& prepared) {
  const World& world = prepared.world();
  const std::vector<std::size_t> objects = glow_target_objects(prepared);
  std::vector<GlowTarget> out;
  for (const MarchObject& o : prepared.objects()) {
    if (!std::binary_search(objects.begin(), objects.end(), o.owner)) continue;
    const double reach = world.objects[o.owner].glow_reach;
    if (const Ball* ball = std::get_if<Ball>(&o.shape)) out.push_back({o.owner, *ball, reach});
    if (const Box* b = std::get_if<Box>(&o.shape)) out.push_back({o.owner, *b, reach});
    if (const Tube* t = std::get_if<Tube>(&o.shape)) out.push_back({o.owner, *t, reach});
  }
  return out;
}

// The weight with which next-event estimation from x picks target g, about
// the solid angle it fills: s² / (s² + |x⁻¹c|²), x⁻¹c its centre seen from
// x, s its size (kernel: glow_pick_weight in march/glow.glsl); 0 for the
// glowing solid whose inner wall x lies on (`inside`, its scene object;
// -1 for none): every direction from there meets that solid or what it
// holds, so cosine-weighted reflection finds its light better than points
// drawn on it (its emission then counts in full where a path meets it).
double glow_pick_weight(const GlowTarget& g, const glm::dvec3& x, int inside) {
  if (static_cast<int>(g.object) == inside) return 0.0;
  const glm::dvec3 v = multiply(inverse(x), g.centre(x));
  const double size = g.size(x), s2 = size * size;
  return s2 / (s2 + glm::dot(v, v));
}

double glow_pick_total(const std::vector<GlowTarget>& glowing, const glm::dvec3& x, int inside) {
  double total = 0.0;
  for (const GlowTarget& g : glowing) total += glow_pick_weight(g, x, inside);
  return total;
}

// The solid whose inner wall the hit lies on (met from inside it: seen so,
// or heading out through its surface, as the quotient's march reports an
// exact ball's inner wall), else -1 (the kernel's inner_wall_of).
int inner_wall_of(const World& world, const MarchHit& hit) {
  const bool solid = hit.object > 0 && is_solid(world.objects[static_cast<std::size_t>(hit.object - 1)].shape);
  return solid && (hit.inside || glm::dot(hit.normal, hit.direction) > 0.0) ? hit.object - 1 : -1;
}

// The geodesics next-event estimation connects x to y of target g by: the
// minimising ones, or with a reach every one up to the distance plus it
// (sol::geodesics_between), shortest first.
std::vector<Connection> glow_connections(const GlowTarget& g, const glm::dvec3& x, const glm::dvec3& y) {
  return g.reach > 0.0 ? geodesics_between(x, y, distance(x, y) + g.reach) : minimising_geodesics(x, y);
}

constexpr double kPathSpreadingTolerance = 1e-6;

// The spreading J of the geodesics a path connects by (sol::sphere_area_density
// at the path tracer's tolerance: within about 1e-6 of the default's 1e-12,
// far below any image's noise, at a tenth of its cost).
double path_spreading(const glm::dvec3& direction, double t) {
  return sphere_area_density(direction, t, kPathSpreadingTolerance);
}

// How far y lies from target g's surface (the target that holds y is the
// nearest): from an exact ball's centre, the squared norm of c⁻¹y; else its bound.
double glow_offset(const GlowTarget& g, const glm::dvec3& y) {
  const glm::dvec3 v = multiply(inverse(g.centre(y)), y);
  return g.closed_form() ? std::abs(g.bound(v)) : glm::dot(v, v);
}

// The area density with which ball g's sampling draws y, where the
// geodesic from x along d met its sphere at L (the hit). In Sol from the
// march's hit: the sphere's outward normal there is its tangent, so the
// geodesic from y back along it ends at the centre after r (checked) with
// the initial direction's opposite. In a quotient the hit's frame may be
// turned by Γ against the cover's (a half turn), so solved, and checked
// to land on the sphere (else y lies on another image's). 0 where neither holds.
double ball_area_density(const Ball& ball, const glm::dvec3& y, const MarchHit& hit, bool quotient) {
  const double r = ball.radius;
  glm::dvec3 from_centre;
  if (quotient) {
    const Connection c = minimising_geodesics(ball.center, y).front();
    if (std::abs(c.length - r) > 1e-3 * std::max(1.0, r)) return 0.0;
    from_centre = glm::normalize(c.direction);
  } else {
    const glm::dvec3 outward = hit.inside ? -hit.normal : hit.normal;
    const ClosedFormGeodesic<double>::State centre = ClosedFormGeodesic<double>(-outward).at(r);
    if (glm::length(multiply(inverse(ball.center), multiply(y, centre.position))) > 1e-3 * std::max(1.0, r)) return 0.0;
    from_centre = -centre.direction;
  }
  const double j_centre = path_spreading(from_centre, r);
  return j_centre > 0.0 ? 1.0 / (4.0 * std::numbers::pi * j_centre) : 0.0;
}

// The density, in solid angle at x, with which next-event estimation picks
// the direction d whose geodesic first meets the glowing scene object
// `object` after L: at y = x exp(L d), on the surface of one of its targets
// (0 where none lists y, or where that geodesic is longer than the
// distance plus the target's reach: next-event estimation never takes it).
double glow_density(const std::vector<GlowTarget>& glowing, std::size_t object, const glm::dvec3& x, int inside,
                    const glm::dvec3& d, double L, const MarchHit& hit, bool quotient) {
  try {
    const glm::dvec3 y = multiply(x, ClosedFormGeodesic<double>(d).at(L).position);
    // The target whose surface holds y: the object's own in Sol, its nearest image in a quotient.
    const GlowTarget* g = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const GlowTarget& b : glowing) {
      if (b.object != object) continue;
      if (const double offset = glow_offset(b, y); offset < nearest) {
        nearest = offset;
        g = &b;
      }
    }
    // (A box's or bound ball's image holds y where y lies on its surface,
    // to the march's tolerance; an exact ball's is checked below.)
    if (!g || (g->closed_form() && nearest > 1e-3)) return 0.0;
    // Shorter than its period, the geodesic is the minimiser (Coiculescu–Schwartz): within any reach.
    if (!(L < (1.0 - 1e-9) * cut_time(d)) && L > (distance(x, y) + g->reach) * (1.0 + 1e-6) + 1e-9) return 0.0;
    const double weight = glow_pick_weight(*g, x, inside);
    if (!(weight > 0.0)) return 0.0;  // (before the area: the inner wall's solid is no target)
    double area = 0.0, cos_y = 0.0;
    if (g->closed_form()) {
      const glm::dvec3 centre = g->centre(x);
      const glm::dvec3 wy = multiply(inverse(centre), y);
      if (g->skips(multiply(inverse(centre), x), wy)) return 0.0;
      // The surface's exact normal at y, against the geodesic's own tangent there.
      cos_y = std::abs(glm::dot(ClosedFormGeodesic<double>(d).direction_at(L), g->normal(wy)));
      area = g->density(wy, g->distance_from(x));
    } else {
      cos_y = std::abs(glm::dot(hit.direction, hit.normal));
      area = ball_area_density(*g->ball(), y, hit, quotient);
    }
    if (!(cos_y > 0.0) || !(area > 0.0)) return 0.0;
    const double pick = weight / glow_pick_total(glowing, x, inside);
    return pick * area * path_spreading(d, L) / cos_y;
  } catch (const OutOfRange&) {
    return 0.0;
  }
}

// A point y of target g's surface, drawn: y, the outward normal there
// (frame components at y) and its area density.
struct GlowPoint {
  glm::dvec3 y, normal;
  double area;
};

GlowPoint glow_point(const GlowTarget& g, const glm::dvec3& x, PathRandom& random) {
  if (g.closed_form()) {
    const double u0 = random.uniform(), u1 = random.uniform(), u2 = random.uniform();
    const double h = g.distance_from(x);
    const glm::dvec3 w = g.point(u0, u1, u2, h);
    return {multiply(g.centre(x), w), g.normal(w), g.density(w, h)};
  }
  const Ball& ball = *g.ball();
  const double u = 2.0 * random.uniform() - 1.0, phi = 2.0 * std::numbers::pi * random.uniform();
  const double s = std::sqrt(std::max(0.0, 1.0 - u * u));
  const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), u);
  const ClosedFormGeodesic<double>::State on_sphere = ClosedFormGeodesic<double>(w).at(ball.radius);
  return {multiply(ball.center, on_sphere.position), on_sphere.direction,
          1.0 / (4.0 * std::numbers::pi * std::max(path_spreading(w, ball.radius), 1e-300))};
}

// Next-event estimation from a diffuse hit (normal n, albedo times the
// path's weight in `weight`): the light of one sampled point of one glowing
// target, along each of its geodesics within reach (glow_connections),
// each weighed by its own J, weighted for `sampling`.
glm::dvec3 glow_sample(const MarchWorld& prepared, const std::vector<GlowTarget>& glowing, const MarchHit& hit,
                       const glm::dvec3& n, PathSampling sampling, PathRandom& random) {
  const World& world = prepared.world();
  const int inside = inner_wall_of(world, hit);
  const double total = glow_pick_total(glowing, hit.point, inside);
  if (!(total > 0.0)) return glm::dvec3(0.0);  // no target from here
  double left = random.uniform() * total;
  std::size_t pick = 0;
  for (double w = glow_pick_weight(glowing[0], hit.point, inside); pick + 1 < glowing.size() && left >= w;
       w = glow_pick_weight(glowing[++pick], hit.point, inside)) {
    left -= w;
  }
  const GlowTarget& g = glowing[pick];
  const double picked = glow_pick_weight(g, hit.point, inside);
  if (!(picked > 0.0)) return glm::dvec3(0.0);  // (rounding past the last target drawn)
  const GlowPoint p = glow_point(g, hit.point, random);
  const glm::dvec3 centre = g.centre(hit.point);
  if (g.skips(multiply(inverse(centre), hit.point), multiply(inverse(centre), p.y))) {
    return glm::dvec3(0.0);  // reflection sampling's alone
  }
  const double area = picked / total * p.area;
  glm::dvec3 light(0.0);
  if (!(area > 0.0)) return light;  // (a point of density 0 is never drawn)
  std::vector<Connection> ways;
  try {
    ways = glow_connections(g, hit.point, p.y);
  } catch (const OutOfRange&) {
    return light;
  }
  for (const Connection& c : ways) {
    if (!(c.length > 0.0)) continue;
    const glm::dvec3 d = glm::normalize(c.direction);
    const double cos_x = glm::dot(n, d);
    if (cos_x <= 0.0) continue;
    const double tolerance = 1e-3 * std::max(1.0, c.length);
    const MarchHit seen = march_from(prepared, hit.point, d);
    if (seen.object != static_cast<int>(g.object) + 1 || std::abs(seen.distance - c.length) > tolerance) {
      continue;  // something, or the target's nearer side, is in the way
    }
    const double cos_y = std::abs(glm::dot(ClosedFormGeodesic<double>(d).direction_at(c.length), p.normal));
    const double spreading = path_spreading(d, c.length);
    if (!(spreading > 0.0)) continue;
    double weight = 1.0;
    if (sampling == PathSampling::Combined) {
      const double glow = area * spreading / std::max(cos_y, 1e-300), reflection = cos_x / std::numbers::pi;
      weight = glow / (glow + reflection);
    }
    light += world.objects[g.object].emission * (weight * cos_x * cos_y / (std::numbers::pi * spreading * area));
  }
  return light;
}

// What one path from a camera ray's first hit brings back. At each hit,
// over the fog of its segment: the object's emission (where the path came
// by a diffuse reflection and next-event estimation could have sampled it
// too, weighted for `sampling`); then with probability `mirror` the path
// goes on along the reflected geodesic (its weight unchanged: the mirror's
// share over its probability), else it is diffuse: the lights' light by
// next-event estimation (light_received, every geodesic to an exact light
// with its 1/J, and shadows) times the albedo, the glowing objects' by
// glow_sample, and the path goes on along a cosine-distributed direction,
// its weight times the albedo (the Lambertian ρ/π times cos θ over the
// density cos θ / π). A path scatters at most World::path_bounces times
// (the camera ray's hit is the first vertex: with 0 a hit's emission and
// the lights' light alone); the glowing objects' next-event estimation, whose
// weight counts on the path going on, is taken only where it may. Russian
// roulette from the fourth hit: the path goes on with probability q =
// min(1, the weight's largest component), its weight divided by q, so
// that no weight ever grows past 1 (a perfect mirror keeps it at 1 and
// the path goes on up to the bounces). Radiance is constant along a
// geodesic, so the estimator needs no more than the geodesics themselves.
// No ambient light.
// `glowing`: next-event estimation's targets (glow_targets; none for
// reflection sampling alone), found once per render.
glm::dvec3 path_radiance(const MarchWorld& prepared, const std::vector<GlowTarget>& glowing, MarchHit hit,
                         PathRandom& random, PathSampling sampling) {
  const World& world = prepared.world();
  glm::dvec3 color(0.0), weight(1.0);
  // The last hit, where it was diffuse (for the emission's weight at the next).
  bool after_diffuse = false;
  glm::dvec3 from(0.0), from_direction(0.0);
  double from_cosine = 0.0;
  int from_inside = -1;  // the solid whose inner wall that hit lies on (inner_wall_of)
  const int bounces = world.path_bounces();
  for (int depth = 0; hit.object != 0; ++depth) {
    const bool goes_on = depth < bounces;  // this vertex may scatter the path further
    const SceneObject& o = world.objects[static_cast<std::size_t>(hit.object - 1)];
    const double transmittance = fog_transmittance(world, hit);
    color += weight * ((1.0 - transmittance) * world.fog_color);
    weight *= transmittance;
    if (o.emission != glm::dvec3(0.0)) {
      double share = 1.0;
      const auto object = static_cast<std::size_t>(hit.object - 1);
      const bool target = std::any_of(glowing.begin(), glowing.end(), [&](const GlowTarget& b) { return b.object == object; });
      if (after_diffuse && target) {
        const double glow =
            glow_density(glowing, object, from, from_inside, from_direction, hit.distance, hit, prepared.features().quotient);
        // Next-event estimation alone counts what it could have drawn (a
        // quotient's images it does not list are left to reflection).
        const double reflection = from_cosine / std::numbers::pi;
        share = sampling == PathSampling::GlowOnly ? (glow > 0.0 ? 0.0 : 1.0) : reflection / (reflection + glow);
      }
      color += weight * o.emission * share;
    }
    const glm::dvec3 n = glm::dot(hit.normal, hit.direction) > 0.0 ? -hit.normal : hit.normal;
    glm::dvec3 next;
    // The material's lobes (sol/materials.h): the specular one with its
    // probability (a random number drawn wherever it has one), its weight
    // over that; else the diffuse one, its share over its probability.
    const glm::dvec3 surface_albedo = albedo_at(o, hit);
    const kernel::SolLobes lobes = material_lobes(o, surface_albedo);
    bool after_specular = false;
    if (lobes.specular_probability > 0.0 && random.uniform() < lobes.specular_probability) {
      next = specular_direction(lobes, hit, n, random);
      after_specular = true;
      weight *= lobes.specular / lobes.specular_probability;
      after_diffuse = false;
    } else {
      const glm::dvec3 albedo = surface_albedo * (lobes.diffuse / (1.0 - lobes.specular_probability));
      if (!world.lights.empty()) color += weight * albedo * light_received(prepared, hit, n);
      if (!glowing.empty() && goes_on) color += weight * albedo * glow_sample(prepared, glowing, hit, n, sampling, random);
      weight *= albedo;
      next = cosine_direction(n, random);
      after_diffuse = true;
      from = hit.point;
      from_inside = inner_wall_of(world, hit);
      from_direction = next;
      from_cosine = glm::dot(n, next);
    }
    if (!goes_on) break;
    if (depth >= 3) {
      const double q = std::min(1.0, std::max({weight.r, weight.g, weight.b}));
      if (!(q > 0.0) || random.uniform() >= q) break;
      weight /= q;
    }
    hit = after_specular ? march_specular(prepared, hit, lobes, n, next) : march_segment(prepared, hit, n, next);
  }
  return color;
}

// Two images of the same height side by side, `left` on the left, with their AOVs.
RenderResult side_by_side(const RenderResult& left, const RenderResult& right) {
  const int h = left.height;
  auto join = [&](const std::vector<float>& a, const std::vector<float>& b, int channels) {
    std::vector<float> out;
    if (a.empty() || b.empty()) return out;  // AOVs not asked for (RenderOptions::aovs)
    out.reserve(a.size() + b.size());
    const std::size_t ra = static_cast<std::size_t>(left.width) * channels, rb = static_cast<std::size_t>(right.width) * channels;
    for (int j = 0; j < h; ++j) {
      out.insert(out.end(), a.begin() + static_cast<std::ptrdiff_t>(j * ra), a.begin() + static_cast<std::ptrdiff_t>((j + 1) * ra));
      out.insert(out.end(), b.begin() + static_cast<std::ptrdiff_t>(j * rb), b.begin() + static_cast<std::ptrdiff_t>((j + 1) * rb));
    }
    return out;
  };
  RenderResult r;
  r.width = left.width + right.width;
  r.height = h;
  r.rgba = join(left.rgba, right.rgba, 4);
  r.object = join(left.object, right.object, 1);
  r.distance = join(left.distance, right.distance, 1);
  r.px = join(left.px, right.px, 1);
  r.py = join(left.py, right.py, 1);
  r.pz = join(left.pz, right.pz, 1);
  r.steps = join(left.steps, right.steps, 1);
  r.albedo = join(left.albedo, right.albedo, 3);
  r.emission = join(left.emission, right.emission, 3);
  r.light_moment = join(left.light_moment, right.light_moment, 1);
  r.samples = left.samples;
  r.normal = join(left.normal, right.normal, 3);
  r.out_of_steps = join(left.out_of_steps, right.out_of_steps, 1);
  r.rays_out_of_steps = left.rays_out_of_steps + right.rays_out_of_steps;
  return r;
}

// ---- Light transport: what a camera ray's hit brings back, behind one
// interface (RenderOptions::transport chooses): the direct light
// (radiance) or one path a sample (path_radiance).
class LightTransport {
 public:
  virtual ~LightTransport() = default;
  /// The colour that sample `sample` of pixel `pixel` (its index in the
  /// eye's image) brings back from its camera ray's hit.
  virtual glm::dvec3 radiance(const MarchHit& hit, std::uint64_t pixel, int sample) const = 0;
};

// Direct light; a glossy lobe's numbers from the seed, the pixel and the
// sample, as a path's.
class DirectLight final : public LightTransport {
 public:
  DirectLight(const MarchWorld& prepared, std::uint64_t seed) : m_prepared(prepared), m_seed(seed) {}
  glm::dvec3 radiance(const MarchHit& hit, std::uint64_t pixel, int sample) const override {
    PathRandom random(m_seed, pixel, static_cast<std::uint64_t>(sample));
    return sol::radiance(m_prepared, hit, random);
  }

 private:
  const MarchWorld& m_prepared;
  std::uint64_t m_seed;
};

// One path a sample, its random numbers from the seed, the pixel and the
// sample (the kernel draws the same); next-event estimation's targets
// found once.
class PathTracer final : public LightTransport {
 public:
  PathTracer(const MarchWorld& prepared, const RenderOptions& settings)
      : m_prepared(prepared),
        m_glowing(settings.path_sampling != PathSampling::ReflectionOnly ? glow_targets(prepared)
                                                                         : std::vector<GlowTarget>()),
        m_seed(settings.seed),
        m_sampling(settings.path_sampling) {}
  glm::dvec3 radiance(const MarchHit& hit, std::uint64_t pixel, int sample) const override {
    PathRandom random(m_seed, pixel, static_cast<std::uint64_t>(sample));
    return path_radiance(m_prepared, m_glowing, hit, random, m_sampling);
  }

 private:
  const MarchWorld& m_prepared;
  std::vector<GlowTarget> m_glowing;
  std::uint64_t m_seed;
  PathSampling m_sampling;
};

std::unique_ptr<LightTransport> make_transport(const MarchWorld& prepared, const RenderOptions& settings) {
  if (settings.transport == Transport::Path) return std::make_unique<PathTracer>(prepared, settings);
  return std::make_unique<DirectLight>(prepared, settings.seed);
}

}  // namespace

// The prepared world, shared with the renders that use it: set_world on
// another thread swaps in a new one while they finish with theirs.
struct CpuRenderer::Held {
  mutable std::mutex guard;
  std::shared_ptr<const MarchWorld> world;

  std::shared_ptr<const MarchWorld> current() const {
    const std::lock_guard lock(guard);
    if (!world) throw std::logic_error("sol::CpuRenderer: no world (call set_world first)");
    return world;
  }
};

CpuRenderer::CpuRenderer() : m_held(std::make_unique<Held>()) {}
CpuRenderer::CpuRenderer(const World& world) : CpuRenderer() { set_world(world); }
CpuRenderer::~CpuRenderer() = default;
CpuRenderer::CpuRenderer(CpuRenderer&&) noexcept = default;
CpuRenderer& CpuRenderer::operator=(CpuRenderer&&) noexcept = default;

void CpuRenderer::set_world(const World& world) {
  set_world(std::make_shared<const MarchWorld>(world));  // (outside the lock: a quotient's field takes a while)
}

void CpuRenderer::set_world(std::shared_ptr<const MarchWorld> prepared) {
  if (!prepared) throw InvalidArgument("sol::CpuRenderer::set_world: no world");
  if (!m_held) m_held = std::make_unique<Held>();  // (a moved-from renderer made whole again)
  const std::lock_guard lock(m_held->guard);
  m_held->world = std::move(prepared);
}

std::shared_ptr<const MarchWorld> CpuRenderer::current_world() const {
  if (!m_held) throw std::logic_error("sol::CpuRenderer: moved from");
  return m_held->current();
}

const MarchWorld& CpuRenderer::world() const { return *current_world(); }

MarchHit CpuRenderer::march(const Camera& camera, const glm::dvec3& direction) const {
  validate(camera);
  const std::shared_ptr<const MarchWorld> prepared = current_world();
  return march_view(*prepared, view_from(*prepared, camera), direction);
}

glm::dvec3 CpuRenderer::shade(const MarchHit& hit) const {
  PathRandom random(0, 0, 0);  // (a glossy reflection: sample 0 of pixel 0, seed 0)
  return radiance(*current_world(), hit, random);
}

RenderResult CpuRenderer::render(std::span<const Camera> eyes, const RenderOptions& options) {
  // The world as it is now (logic_error without one), whatever set_world does meanwhile.
  const std::shared_ptr<const MarchWorld> prepared = current_world();
  // Peak memory per pixel, measured: 55 bytes (the result's colour and
  // AOVs, 40, and the tiles' working copies) before the guides' albedo,
  // emission and normal (36 more), rounded up.
  validate_render(eyes, options, "sol::CpuRenderer::render", 96.0);
  // Each eye on its own; the progress of all of them together.
  RenderOptions eye_options = options;
  RenderResult r;
  for (std::size_t e = 0; e < eyes.size(); ++e) {
    if (options.progress) {
      eye_options.progress = [&, e](double f) { options.progress((static_cast<double>(e) + f) / static_cast<double>(eyes.size())); };
    }
    RenderResult eye = render_eye(*prepared, eyes[e], eye_options);
    r = e == 0 ? std::move(eye) : side_by_side(r, eye);
  }
  if (options.rows) {  // the colour handed over, not kept
    options.rows(0, r.height, r.rgba);
    std::vector<float>().swap(r.rgba);
  }
  return r;
}

std::string CpuRenderer::description() const {
  return "cpu (" + std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " threads)";
}

// One eye (validated by render()).
RenderResult CpuRenderer::render_eye(const MarchWorld& prepared, const Camera& camera, const RenderOptions& settings) {
  const int w = settings.width, h = settings.height;
  const auto pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  RenderResult r;
  r.width = w;
  r.height = h;
  r.rgba.assign(4 * pixels, 0.0f);
  const bool aovs = settings.aovs;
  if (aovs) {
    for (auto* plane : {&r.object, &r.distance, &r.px, &r.py, &r.pz, &r.steps, &r.out_of_steps}) plane->assign(pixels, 0.0f);
    if (settings.guides) r.normal.assign(3 * pixels, 0.0f);
  }
  const bool guides = settings.guides;  // (the albedo and emission; the normal with the AOVs)
  if (guides) {
    for (auto* plane : {&r.albedo, &r.emission}) plane->assign(3 * pixels, 0.0f);
    r.light_moment.assign(pixels, 0.0f);
  }
  r.samples = settings.samples;
  std::atomic<std::uint64_t> out_of_steps{0};

  // Every ray starts at the camera, except an ODS eye's: each column at its
  // own eye (sol::column_eye), prepared once per column.
  const bool ods = camera.projection == Projection::Equirectangular && camera.eye_offset != 0.0;
  std::vector<CameraView> views;
  std::vector<glm::dmat3> transports;
  Camera mono = camera;
  mono.eye_offset = 0.0;
  for (int i = 0; i < (ods ? w : 1); ++i) {
    const ColumnEye column = column_eye(camera, i, w);
    Camera at = camera;
    at.position = multiply(camera.position, column.offset);
    views.push_back(view_from(prepared, at));
    transports.push_back(column.transport);
  }
  // The ray of a point of pixel (i, j) in sample s: from its column's eye;
  // with a lens from sample s's lens point (sol::lens_ray).
  const bool lens = camera.aperture > 0.0;
  auto march_at = [&](int i, int j, const glm::dvec2& offset, int s) {
    if (lens) {
      const LensRay ray = lens_ray(camera, camera_ray(camera, i, j, w, h, offset), lens_sample(s));
      if (ray.start == glm::dvec3(0.0)) return march_view(prepared, views[0], ray.direction);
      Camera at = camera;
      at.position = multiply(camera.position, ray.start);
      return march_view(prepared, view_from(prepared, at), ray.direction);
    }
    if (!ods) return march_view(prepared, views[0], camera_ray(camera, i, j, w, h, offset));
    const std::size_t c = static_cast<std::size_t>(i);
    return march_view(prepared, views[c], glm::normalize(transports[c] * camera_ray(mono, i, j, w, h, offset)));
  };
  const std::unique_ptr<LightTransport> transport = make_transport(prepared, settings);
  unsigned threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(h));
  detail::for_each_row(h, threads, settings.progress, [&](int j, const std::atomic<bool>& stopping) {
    if (settings.cancel && settings.cancel->load()) throw Cancelled("sol::CpuRenderer::render: cancelled");
    for (int i = 0; i < w; ++i) {
      // A row of many samples can take seconds: once the render stops (an
      // error elsewhere, a cancelled progress), the rest of it is dropped.
      if (stopping.load(std::memory_order_relaxed)) return;
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i);
      t_out_of_steps = 0;  // this pixel's marches from here
      // Outside a fisheye's image circle there is no ray: black, no hit.
      // Sample 0 (the centre: the AOVs' hit) where the range starts there.
      const int first = settings.first_sample;
      const bool sees = first == 0 && camera_sees(camera, i, j, w, h);
      const MarchHit hit = sees ? march_at(i, j, {0.5, 0.5}, 0) : MarchHit{};
      // Each sample's colour, and with the guides its first hit's albedo and
      // emission (their means) and the square of its light's luminance (the
      // colour less the emission: its mean the denoiser's light moment).
      glm::dvec3 albedo(0.0), emission(0.0);
      double moment = 0.0;
      const auto colour = [&](const MarchHit& at, int s) {
        const glm::dvec3 radiance = transport->radiance(at, k, s);
        if (guides) {
          const FirstHitGuides g = first_hit_guides(prepared.world(), at);
          albedo += g.albedo;
          emission += g.emission;
          moment += std::pow(kernel::sol_denoise_luminance(radiance - g.emission), 2.0);
        }
        return radiance;
      };
      glm::dvec3 c = sees ? colour(hit, 0) : glm::dvec3(0.0);
      for (int s = std::max(first, 1); s < first + settings.samples; ++s) {  // the other samples: no AOVs but the guides
        const glm::dvec2 offset = pixel_sample(s);
        if (!camera_sees(camera, i, j, w, h, offset)) continue;
        const MarchHit other = march_at(i, j, offset, s);
        c += colour(other, s);
      }
      c /= static_cast<double>(settings.samples);
      albedo /= static_cast<double>(settings.samples);
      emission /= static_cast<double>(settings.samples);
      r.rgba[4 * k + 0] = static_cast<float>(c.r);
      r.rgba[4 * k + 1] = static_cast<float>(c.g);
      r.rgba[4 * k + 2] = static_cast<float>(c.b);
      r.rgba[4 * k + 3] = 1.0f;
      out_of_steps.fetch_add(t_out_of_steps, std::memory_order_relaxed);
      for (int channel = 0; channel < 3 && guides; ++channel) {
        r.albedo[3 * k + channel] = static_cast<float>(albedo[channel]);
        r.emission[3 * k + channel] = static_cast<float>(emission[channel]);
      }
      if (guides) r.light_moment[k] = static_cast<float>(moment / static_cast<double>(settings.samples));
      if (!aovs) continue;
      r.out_of_steps[k] = static_cast<float>(t_out_of_steps);
      r.object[k] = static_cast<float>(hit.object);
      r.steps[k] = static_cast<float>(hit.steps);
      if (hit.object != 0) {
        r.distance[k] = static_cast<float>(hit.distance);
        r.px[k] = static_cast<float>(hit.point.x);
        r.py[k] = static_cast<float>(hit.point.y);
        r.pz[k] = static_cast<float>(hit.point.z);
        for (int channel = 0; channel < 3 && guides; ++channel) r.normal[3 * k + channel] = static_cast<float>(hit.normal[channel]);
      }
    }
  });
  r.rays_out_of_steps = out_of_steps.load();
  return r;
}

MarchHit march(const Scene& scene, const glm::dvec3& direction) {
  return CpuRenderer(scene).march(scene.camera, direction);
}

glm::dvec3 shade(const Scene& scene, const MarchHit& hit) {
  PathRandom random(0, 0, 0);
  return radiance(MarchWorld(scene), hit, random);
}

RenderResult render_cpu(const Scene& scene, const RenderOptions& options) {
  CpuRenderer renderer;
  return render_scene(renderer, scene, options);
}

RenderResult render_cpu_stereo(const Scene& scene, const RenderOptions& options, double ipd) {
  return CpuRenderer(scene).render_stereo(scene.camera, ipd, options);
}

}  // namespace sol

namespace sol::detail {

void for_each_row(int rows, unsigned threads, const std::function<void(double)>& progress,
                  const std::function<void(int, const std::atomic<bool>&)>& row) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kInterval = std::chrono::milliseconds(200);
  std::atomic<int> next{0}, done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto fail = [&] {
    const std::lock_guard<std::mutex> lock(error_mutex);
    if (!error) error = std::current_exception();
    failed = true;
  };
  // The calling thread reports (and so may be stopped by `progress`) every
  // kInterval, between its own rows once it takes rows too.
  auto last_report = Clock::now();
  auto report = [&] {
    if (!progress || Clock::now() - last_report < kInterval) return;
    last_report = Clock::now();
    progress(static_cast<double>(done.load()) / rows);
  };
  auto worker = [&](bool reporter) {
    try {
      for (int j = next++; j < rows && !failed; j = next++) {
        row(j, failed);
        ++done;
        if (reporter) report();
      }
    } catch (...) {
      fail();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (unsigned k = 1; k < threads; ++k) pool.emplace_back(worker, false);
    try {
      if (progress) progress(0.0);
      while (progress && !pool.empty() && done.load() < rows && next.load() < rows && !failed) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        report();
      }
    } catch (...) {
      fail();  // the others stop at their next row
    }
    worker(true);  // the calling thread takes the rows left
  }  // joins the pool
  if (error) std::rethrow_exception(error);
  if (progress) progress(1.0);
}

}  // namespace sol::detail
