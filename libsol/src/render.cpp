#include "sol/render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

#include "sol/closed_form.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/error.hpp"
#include "sol/geodesic.hpp"
#include "sol/group.hpp"
#include "sol/lattice.hpp"

namespace sol {

double object_distance(const MarchObject& o, const glm::dvec3& q) {
  switch (o.type) {
    case ObjectType::PlaneX:
      return sdf_plane_x(q, o.c);
    case ObjectType::PlaneY:
      return sdf_plane_y(q, o.c);
    case ObjectType::PlaneZ:
      return sdf_plane_z(q, o.c);
    case ObjectType::Ball:
      return o.exact ? sdf_ball_exact(q, o.center, o.radius) : sdf_ball(q, o.center, o.radius);
    case ObjectType::Tube:
      return o.axis == kAxisZ ? sdf_tube(q, o.center, kAxisZ, o.radius)
                              : sdf_tube_horizontal(q, o.center, o.heading, o.radius);
  }
  return std::numeric_limits<double>::infinity();
}

namespace {

using RelativeObject = MarchObject;

// The unit normal at a hit q (camera-relative), facing the camera's side:
// the march stops within hit_epsilon of a plane, possibly just across it,
// so a plane's side comes from the camera (the origin), not from q. Balls:
// the gradient of the distance bound by central differences along the frame
// E1 = e^{z}∂x, E2 = e^{-z}∂y, E3 = ∂z (the same step as the kernel's).
glm::dvec3 object_normal(const RelativeObject& o, const glm::dvec3& q) {
  if (o.type == ObjectType::Ball && o.exact) {
    try {
      return sdf_ball_exact_gradient(q, o.center);  // the true sphere's normal
    } catch (const OutOfRange&) {
    }
  }
  if (o.type == ObjectType::Ball || o.type == ObjectType::Tube) {
    const double h = kernel::kNormalStep, ez = std::exp(q.z);
    const glm::dvec3 e1(h * ez, 0.0, 0.0), e2(0.0, h / ez, 0.0), e3(0.0, 0.0, h);
    const glm::dvec3 g(object_distance(o, q + e1) - object_distance(o, q - e1),
                       object_distance(o, q + e2) - object_distance(o, q - e2),
                       object_distance(o, q + e3) - object_distance(o, q - e3));
    return glm::length(g) > 0.0 ? glm::normalize(g) : glm::dvec3(0.0, 0.0, 1.0);
  }
  const double side = 0.0 >= o.c ? 1.0 : -1.0;
  glm::dvec3 n{0.0, 0.0, side};
  if (o.type == ObjectType::PlaneX) {
    n = sdf_plane_x_gradient(q, o.c);
    n.x = side * std::abs(n.x);
  } else if (o.type == ObjectType::PlaneY) {
    n = sdf_plane_y_gradient(q, o.c);
    n.y = side * std::abs(n.y);
  }
  return n;
}

// Pattern factor from the hit's coordinates in the plane (world).
double pattern_factor(Pattern pattern, double u, double v) {
  switch (pattern) {
    case Pattern::None:
      return 1.0;
    case Pattern::Circles: {
      const double du = u - std::floor(u) - 0.5, dv = v - std::floor(v) - 0.5;
      return du * du + dv * dv < kernel::kCircleRadius * kernel::kCircleRadius ? 1.0 : kernel::kCircleDark;
    }
    case Pattern::Checker:
      return std::fmod(std::floor(u) + std::floor(v), 2.0) == 0.0 ? 1.0 : kernel::kCheckerDark;
  }
  return 1.0;
}

void require_size(int value, const char* name) {
  if (value < 1 || value > 16384) {
    throw InvalidArgument(std::string("sol::render_cpu: ") + name + " must be in [1, 16384], got " +
                          std::to_string(value));
  }
}

}  // namespace

CameraBasis camera_basis(const Camera& camera) {
  const glm::dvec3 forward = glm::normalize(camera.forward);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  return {right, glm::cross(right, forward), forward, std::tan(camera.fov * 0.5 * 3.14159265358979323846 / 180.0)};
}

glm::dvec4 image_window(const Camera& camera, int width, int height) {
  if (camera.frustum) return {camera.frustum->left, camera.frustum->right, camera.frustum->up, camera.frustum->down};
  const double t = std::tan(camera.fov * 0.5 * 3.14159265358979323846 / 180.0);
  const double aspect = static_cast<double>(width) / height;
  return {-t * aspect, t * aspect, t, -t};
}

glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height) {
  const CameraBasis b = camera_basis(camera);
  const glm::dvec4 window = image_window(camera, width, height);
  const double sx = window.x + (window.y - window.x) * (i + 0.5) / width;
  const double sy = window.z + (window.w - window.z) * (j + 0.5) / height;
  return glm::normalize(sx * b.right + sy * b.up + b.forward);
}

namespace {

// A scene object in world coordinates, as the march sees it.
MarchObject world_object(const SceneObject& o, std::size_t owner) {
  MarchObject r{o.type, o.c, o.center, o.radius, o.axis, owner, glm::dvec2(0.0), o.exact};
  if (o.type == ObjectType::Tube && o.axis != kAxisZ) {
    const glm::dvec3 d = tube_axis_direction(o.axis);
    r.heading = {d.x, d.y};
  }
  return r;
}

}  // namespace

MarchObject relative_to(const MarchObject& o, const glm::dvec3& p) {
  MarchObject r = o;
  switch (o.type) {
    case ObjectType::PlaneX:
      r.c = std::exp(-p.z) * (o.c - p.x);
      break;
    case ObjectType::PlaneY:
      r.c = std::exp(p.z) * (o.c - p.y);
      break;
    case ObjectType::PlaneZ:
      r.c = o.c - p.z;
      break;
    case ObjectType::Ball:
    case ObjectType::Tube:
      r.center = multiply(inverse(p), o.center);
      // p⁻¹ maps (x, y, z) to (e^{-p_z}(x - p_x), e^{p_z}(y - p_y), z - p_z).
      if (o.type == ObjectType::Tube && o.axis != kAxisZ) {
        r.heading = glm::normalize(glm::dvec2(std::exp(-p.z) * o.heading.x, std::exp(p.z) * o.heading.y));
      }
      break;
  }
  return r;
}

MarchObject relative_object(const SceneObject& o, const glm::dvec3& p, std::size_t owner) {
  return relative_to(world_object(o, owner), p);
}

double cutout_gap_bound(Pattern pattern, const glm::dvec3& w) {
  const double ez = std::exp(w.z);
  const double fu = w.x - std::floor(w.x), fv = w.y - std::floor(w.y);
  if (pattern == Pattern::Checker) {
    if (std::fmod(std::floor(w.x) + std::floor(w.y), 2.0) == 0.0) return 0.0;  // on a light square
    // The nearest light squares share an edge with this dark one.
    return std::asinh(std::min(std::min(fu, 1.0 - fu) / ez, std::min(fv, 1.0 - fv) * ez));
  }
  if (pattern != Pattern::Circles) return 0.0;
  // The nearest disc is this cell's (the cells are the grid's Voronoi cells).
  const double du = std::abs(fu - 0.5), dv = std::abs(fv - 0.5);
  const double r = kernel::kCircleRadius;
  const double boxes = std::max(std::max(0.0, du - r) / ez, std::max(0.0, dv - r) * ez);
  const double gap = std::max(0.0, std::hypot(du, dv) - r);
  return std::asinh(std::max(boxes, std::min(ez, 1.0 / ez) * gap / std::sqrt(2.0)));
}

glm::dvec2 pattern_coordinates(const MarchObject& o, const glm::dvec3& q) {
  constexpr double kCells = kernel::kPatternCellsPerRadian;  // 8 cells per turn
  switch (o.type) {
    case ObjectType::PlaneX:
      return {q.y, q.z};
    case ObjectType::PlaneY:
      return {q.x, q.z};
    case ObjectType::PlaneZ:
      return {q.x, q.y};
    case ObjectType::Ball: {
      const glm::dvec3 w = multiply(inverse(o.center), q);
      return {kCells * std::atan2(w.y, w.x), kCells * std::atan2(w.z, std::hypot(w.x, w.y))};
    }
    case ObjectType::Tube: {
      const glm::dvec3 w = multiply(inverse(o.center), q);
      if (o.axis == kAxisZ) return {kCells * std::atan2(w.y, w.x), kCells * w.z / o.radius};
      // The axis direction relative to the point `center` (see relative_to).
      const glm::dvec2 h =
          glm::normalize(glm::dvec2(std::exp(-o.center.z) * o.heading.x, std::exp(o.center.z) * o.heading.y));
      const double along = w.x * h.x + w.y * h.y, across = w.y * h.x - w.x * h.y;
      return {kCells * std::atan2(w.z, across), kCells * along / o.radius};
    }
  }
  return {0.0, 0.0};
}

namespace {

double gap(double v, double lo, double hi) { return v < lo ? lo - v : (v > hi ? v - hi : 0.0); }

// A lower bound, over every point q of D, of object_distance(o, q) (world
// coordinates). D = {s γ1 + r γ2} × [0, h): its (x, y) lie in the
// parallelogram P with corners 0, γ1, γ2, γ1 + γ2. D is cut into slabs
// z in [z0, z1] and the bound is the least of the slabs' bounds:
//  - plane z = c: |q_z - c| >= the gap between c and [z0, z1];
//  - ball, vertical tube: the distance bound is at least the distance to the
//    plane x = c_x, asinh(|q_x - c_x| e^{-q_z}) >= asinh(gap_x e^{-z1}), and
//    to y = c_y, asinh(|q_y - c_y| e^{q_z}) >= asinh(gap_y e^{z0}) (gap_x,
//    gap_y: from c_x, c_y to P's x- and y-ranges); balls also >= |Δz|;
//  - horizontal tube: |h_y Δx - h_x Δy| is linear on P, so its least value
//    is 0 when the corners' values differ in sign and else the least corner
//    value; the denominator |h_x| e^{-z} + |h_y| e^{z} is convex in z, so at
//    most its larger value at z0 or z1; also >= |Δz|.
double lower_bound_over_domain(const MarchObject& o, const Lattice& lattice) {
  const double h = lattice.height();
  if (o.type == ObjectType::PlaneZ) return gap(o.c, 0.0, h);
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  const glm::dvec2 corners[4] = {{0.0, 0.0}, {g1.x, g1.y}, {g2.x, g2.y}, {g1.x + g2.x, g1.y + g2.y}};
  double xlo = 0.0, xhi = 0.0, ylo = 0.0, yhi = 0.0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;  // h_y Δx - h_x Δy over P
  const glm::dvec3& c = o.center;
  for (const glm::dvec2& k : corners) {
    xlo = std::min(xlo, k.x);
    xhi = std::max(xhi, k.x);
    ylo = std::min(ylo, k.y);
    yhi = std::max(yhi, k.y);
    const double v = o.heading.y * (k.x - c.x) - o.heading.x * (k.y - c.y);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const bool horizontal = o.type == ObjectType::Tube && o.axis != kAxisZ;
  const double least_across = lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(std::abs(lo), std::abs(hi));
  const double gx = gap(c.x, xlo, xhi), gy = gap(c.y, ylo, yhi);
  const double hx = std::abs(o.heading.x), hy = std::abs(o.heading.y);
  constexpr int kSlabs = 16;
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kSlabs; ++i) {
    const double z0 = h * i / kSlabs, z1 = h * (i + 1) / kSlabs;
    double b = 0.0;
    if (horizontal) {
      const double denominator = std::max(hx * std::exp(-z0) + hy * std::exp(z0), hx * std::exp(-z1) + hy * std::exp(z1));
      b = std::max(gap(c.z, z0, z1), std::asinh(least_across / denominator));
    } else {
      b = std::max(std::asinh(gx * std::exp(-z1)), std::asinh(gy * std::exp(z0)));
      if (o.type == ObjectType::Ball) b = std::max(b, gap(c.z, z0, z1));
    }
    least = std::min(least, b);
  }
  return least - o.radius;
}

// Whether two images are the same set (tubes: the same line).
bool same_image(const MarchObject& a, const MarchObject& b) {
  if (a.type != b.type || a.owner != b.owner) return false;
  constexpr double kTolerance = 1e-9;
  if (a.type == ObjectType::PlaneZ) return std::abs(a.c - b.c) < kTolerance;
  if (a.type != ObjectType::Tube) return glm::length(a.center - b.center) < kTolerance;
  if (a.axis == kAxisZ) return std::abs(a.center.x - b.center.x) < kTolerance && std::abs(a.center.y - b.center.y) < kTolerance;
  const glm::dvec2 d(b.center.x - a.center.x, b.center.y - a.center.y);
  return std::abs(a.center.z - b.center.z) < kTolerance &&
         std::abs(a.heading.x * b.heading.y - a.heading.y * b.heading.x) < kTolerance &&
         std::abs(a.heading.x * d.y - a.heading.y * d.x) < kTolerance;
}

}  // namespace

// Why these images are all a march step can reach. A step starts at a point
// q of D and is at most kQuotientMaxStep (0.5) long, and object_distance is
// a lower bound of the distance to the drawn object; so an image whose bound
// exceeds 0.5 all over D is never reached, and lower_bound_over_domain
// (above) proves that for the images dropped here. The enumeration is wide
// enough: (1) |c| >= 2 moves an object, first moved into the cells z in
// [0, h), by at least h = 0.962 in z from D, beyond 0.5 + radius while the
// radius is at most kMaxQuotientRadius (0.45; validate checks it); (2) an
// image within reach lies over x in [-3.1, φ + 4.1], y in [-2.2, φ + 1.2]
// (asinh(gap e^{-h}) <= 0.95), whose lattice coordinates are below 3.4 in
// size, while γ3^{±1} moves a point of D to lattice coordinates below 3 (the
// entries of [[2,1],[1,1]] and its inverse), so |a|, |b| <= 7 suffice for
// balls and vertical lines; a horizontal line along a lattice vector of
// length <= 4.3 has a point γ3^c o + λ within 4.3 of any of its points, which
// adds at most 2.3 to |a|, |b|. The test Quotient.ImagesAreCompleteAndReachable
// checks that a wider enumeration finds nothing more.
std::vector<MarchObject> quotient_images(const Scene& scene) {
  const Lattice lattice = Lattice::golden();
  constexpr int kRange = 10;
  std::vector<MarchObject> images;
  const double h = lattice.height();
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    MarchObject base = world_object(scene.objects[i], i);
    if (base.type == ObjectType::PlaneZ) {
      base.c -= h * std::floor(base.c / h);
    } else {
      // Move the centre (axis point) into D, the axis along with it.
      const Teleport t = lattice.teleport(base.center);
      base = relative_to(base, inverse(t.element));
      base.center = t.point;
    }
    const int range = base.type == ObjectType::PlaneZ ? 0 : kRange;  // (x, y) translations fix planes z = c
    for (int c = -1; c <= 1; ++c) {
      for (int a = -range; a <= range; ++a) {
        for (int b = -range; b <= range; ++b) {
          const MarchObject image = relative_to(base, inverse(lattice.element(a, b, c)));
          if (lower_bound_over_domain(image, lattice) > kQuotientMaxStep) continue;
          if (std::none_of(images.begin(), images.end(), [&](const MarchObject& m) { return same_image(m, image); })) {
            images.push_back(image);
          }
        }
      }
    }
  }
  return images;
}

namespace {

// What every ray of a render shares, computed once per render: the objects
// relative to the camera (cover) or their images around D (quotient).
struct PreparedScene {
  std::vector<MarchObject> objects;
  bool heights_only = true;  // only planes z = c: the march needs z alone (and culls by the z-range)
  bool cutout_gaps = false;  // cutout planes z = c: their gap bounds need the full position
};

PreparedScene prepare(const Scene& scene) {
  PreparedScene p;
  if (scene.quotient == Quotient::Golden) {
    p.objects = quotient_images(scene);
    p.heights_only = false;
    return p;
  }
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    p.objects.push_back(relative_object(scene.objects[k], scene.camera.position, k));
    p.heights_only = p.heights_only && scene.objects[k].type == ObjectType::PlaneZ;
    p.cutout_gaps = p.cutout_gaps || (scene.objects[k].cutout && scene.objects[k].type == ObjectType::PlaneZ);
  }
  return p;
}

MarchHit march_cover(const Scene& scene, const PreparedScene& prepared, const glm::dvec3& direction) {
  const glm::dvec3 origin = scene.camera.position;
  const std::vector<MarchObject>& objects = prepared.objects;
  const std::size_t n = objects.size();
  const bool heights_only = prepared.heights_only;
  const ClosedFormGeodesic<double> ray(direction);
  MarchHit hit;
  if (heights_only) {
    // Exact culling: z stays within [min_height, max_height] along the whole
    // geodesic, so planes z = c outside that range (by more than the hit
    // epsilon) are never reached. A ray that reaches none is a miss with 0 steps.
    const double lo = ray.min_height() - scene.hit_epsilon, hi = ray.max_height() + scene.hit_epsilon;
    bool reachable = false;
    for (std::size_t k = 0; k < n; ++k) reachable = reachable || (objects[k].c >= lo && objects[k].c <= hi);
    if (!reachable) return hit;
  }
  double t = 0.0;
  // Cutout planes the ray is passing through (between their discs): not hits
  // until the ray is 2 hit_epsilon away from them again; meanwhile the step
  // is at least 2 hit_epsilon, so the ray leaves the plane.
  std::uint64_t passing = 0;
  for (int step = 0; step < scene.max_steps; ++step) {
    const bool full = !heights_only || prepared.cutout_gaps;
    const glm::dvec3 q = full ? ray.at(t).position : glm::dvec3(0.0, 0.0, ray.height_at(t));
    double nearest = std::numeric_limits<double>::infinity(), nearest_hit = nearest;
    std::size_t hit_k = 0;
    for (std::size_t k = 0; k < n; ++k) {
      double d = object_distance(objects[k], q);
      const SceneObject& o = scene.objects[k];
      if (o.cutout && o.type == ObjectType::PlaneZ) d = std::max(d, cutout_gap_bound(o.pattern, multiply(origin, q)));
      const std::uint64_t bit = std::uint64_t{1} << k;
      if ((passing & bit) && d > 2.0 * scene.hit_epsilon) passing &= ~bit;
      nearest = std::min(nearest, d);
      if (!(passing & bit) && d < nearest_hit) {
        nearest_hit = d;
        hit_k = k;
      }
    }
    hit.steps = step + 1;
    if (nearest_hit < scene.hit_epsilon) {
      const glm::dvec3 p = full ? q : ray.at(t).position;  // the full position, once
      const SceneObject& o = scene.objects[hit_k];
      const glm::dvec3 world = multiply(origin, p);
      // Planes: their own world coordinates; balls, tubes: relative to the
      // centre (axis point), left-invariant, so camera-relative coordinates do.
      const bool plane = o.type != ObjectType::Ball && o.type != ObjectType::Tube;
      const glm::dvec2 uv = pattern_coordinates(objects[hit_k], plane ? world : p);
      if (o.cutout && pattern_factor(o.pattern, uv.x, uv.y) != 1.0) {
        passing |= std::uint64_t{1} << hit_k;  // between the discs: go through
        t += std::max(nearest, 2.0 * scene.hit_epsilon);
        if (t > scene.max_distance) break;
        continue;
      }
      hit.object = static_cast<int>(hit_k) + 1;
      hit.distance = t;
      hit.point = world;
      hit.normal = object_normal(objects[hit_k], p);
      hit.pattern_uv = uv;
      return hit;
    }
    t += passing ? std::max(nearest, 2.0 * scene.hit_epsilon) : nearest;
    if (t > scene.max_distance) break;
  }
  hit.distance = std::min(t, scene.max_distance);
  return hit;
}

// The march in Γ\Sol: the ray lives in D. Every step starts in D (a ray
// found outside is first teleported back by an element of Γ; its direction,
// in frame components, is unchanged by the left-translation, and its
// closed-form geodesic restarts there) and is at most kMaxStep long. The
// distance bounds of all images of the objects in the cells around D are in
// the step, so a step may cross a face of D but never passes through an
// object beyond it. For speed only the images within kKeep of the last
// filter point are evaluated, and the step is also kept below kKeep minus
// the arc length since that filter, so that no dropped image can be reached
// (a dropped image's bound exceeded kKeep there, and bounds are 1-Lipschitz
// lower bounds of the distance).
MarchHit march_quotient(const Scene& scene, const PreparedScene& prepared, const glm::dvec3& direction) {
  constexpr double kMaxStep = kQuotientMaxStep, kKeep = kernel::kQuotientKeep;
  const Lattice lattice = Lattice::golden();
  const std::vector<MarchObject>& images = prepared.objects;
  glm::dvec3 origin = lattice.teleport(scene.camera.position).point;
  auto ray = std::make_unique<ClosedFormGeodesic<double>>(direction);
  std::vector<std::size_t> kept;
  double since_filter = kKeep;  // forces a filter at the start
  MarchHit hit;
  double t = 0.0, local = 0.0;  // total arc length; arc length since the last teleport
  for (int step = 0; step < scene.max_steps; ++step) {
    glm::dvec3 q = multiply(origin, ray->at(local).position);
    if (!lattice.contains(q)) {
      const glm::dvec3 u = ray->direction_at(local);
      origin = lattice.teleport(q).point;
      ray = std::make_unique<ClosedFormGeodesic<double>>(u);
      local = 0.0;
      q = origin;
      since_filter = kKeep;
    }
    if (kKeep - since_filter < kernel::kQuotientRefilter) {
      kept.clear();
      for (std::size_t k = 0; k < images.size(); ++k) {
        if (object_distance(images[k], q) <= kKeep) kept.push_back(k);
      }
      since_filter = 0.0;
    }
    double nearest = std::numeric_limits<double>::infinity();
    std::size_t nearest_k = 0;
    for (std::size_t k : kept) {
      const double d = object_distance(images[k], q);
      if (d < nearest) {
        nearest = d;
        nearest_k = k;
      }
    }
    hit.steps = step + 1;
    if (nearest < scene.hit_epsilon) {
      hit.object = static_cast<int>(images[nearest_k].owner) + 1;
      hit.distance = t;
      hit.point = q;
      // Normals are left-invariant: evaluate relative to the segment's origin
      // (a plane then faces the side the ray comes from, as in the cover).
      hit.normal = object_normal(relative_to(images[nearest_k], origin), multiply(inverse(origin), q));
      hit.pattern_uv = pattern_coordinates(images[nearest_k], q);  // world coordinates, the image's own
      return hit;
    }
    const double step_length = std::min({nearest, kMaxStep, kKeep - since_filter});
    t += step_length;
    local += step_length;
    since_filter += step_length;
    if (t > scene.max_distance) break;
  }
  hit.distance = std::min(t, scene.max_distance);
  return hit;
}


MarchHit march_prepared(const Scene& scene, const PreparedScene& prepared, const glm::dvec3& direction) {
  return scene.quotient == Quotient::Golden ? march_quotient(scene, prepared, direction)
                                            : march_cover(scene, prepared, direction);
}

}  // namespace

MarchHit march(const Scene& scene, const glm::dvec3& direction) {
  return march_prepared(scene, prepare(scene), direction);
}

glm::dvec3 shade(const Scene& scene, const MarchHit& hit) {
  if (hit.object == 0) return glm::dvec3(0.0);
  const SceneObject& o = scene.objects[static_cast<std::size_t>(hit.object - 1)];
  const glm::dvec3& p = hit.point;
  glm::dvec3 light(0.0);
  for (const Light& l : scene.lights) {
    for (const LightAtPoint& at : lights_at(l, p)) {
      light += l.color * (l.intensity * at.attenuation * std::max(0.0, glm::dot(hit.normal, at.direction)));
    }
  }
  const glm::dvec3 surface = o.color * pattern_factor(o.pattern, hit.pattern_uv.x, hit.pattern_uv.y) * (scene.ambient + (1.0 - scene.ambient) * light);
  const double transmittance = std::exp(-scene.fog_density * hit.distance);
  return scene.fog_color + (surface - scene.fog_color) * transmittance;
}

RenderResult render_cpu(const Scene& scene, const RenderSettings& settings) {
  validate(scene);
  require_size(settings.width, "width");
  require_size(settings.height, "height");
  const int w = settings.width, h = settings.height;
  const auto pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  RenderResult r;
  r.width = w;
  r.height = h;
  r.rgba.assign(4 * pixels, 0.0f);
  r.object.assign(pixels, 0.0f);
  r.distance.assign(pixels, 0.0f);
  r.px.assign(pixels, 0.0f);
  r.py.assign(pixels, 0.0f);
  r.pz.assign(pixels, 0.0f);
  r.steps.assign(pixels, 0.0f);

  const PreparedScene prepared = prepare(scene);  // shared by every ray
  std::atomic<int> next_row{0}, rows_done{0};
  auto worker = [&]() {
    for (int j = next_row++; j < h; j = next_row++) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i);
        const MarchHit hit = march_prepared(scene, prepared, camera_ray(scene.camera, i, j, w, h));
        const glm::dvec3 c = shade(scene, hit);
        r.rgba[4 * k + 0] = static_cast<float>(c.r);
        r.rgba[4 * k + 1] = static_cast<float>(c.g);
        r.rgba[4 * k + 2] = static_cast<float>(c.b);
        r.rgba[4 * k + 3] = 1.0f;
        r.object[k] = static_cast<float>(hit.object);
        r.steps[k] = static_cast<float>(hit.steps);
        if (hit.object != 0) {
          r.distance[k] = static_cast<float>(hit.distance);
          r.px[k] = static_cast<float>(hit.point.x);
          r.py[k] = static_cast<float>(hit.point.y);
          r.pz[k] = static_cast<float>(hit.point.z);
        }
      }
      ++rows_done;
    }
  };
  unsigned threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(h));
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < threads; ++k) pool.emplace_back(worker);
  if (settings.progress) {
    // The calling thread reports progress while the pool works.
    if (pool.empty()) {
      worker();
    } else {
      while (rows_done.load() < h) {
        settings.progress(static_cast<double>(rows_done.load()) / h);
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        if (next_row.load() >= h) break;
      }
    }
  } else {
    worker();
  }
  if (settings.progress && !pool.empty()) worker();  // help with any rows left
  for (std::thread& t : pool) t.join();
  if (settings.progress) settings.progress(1.0);
  return r;
}

LightAtPoint light_at(const Light& light, const glm::dvec3& p) {
  if (light.type == LightType::Directional) return {glm::normalize(light.direction), 1.0};
  const glm::dvec3 d = light.position - p;
  // The coordinate difference in frame components at p (left-invariant, like
  // everything here), and the inverse-square law on the distance bound.
  const glm::dvec3 v(std::exp(-p.z) * d.x, std::exp(p.z) * d.y, d.z);
  const double r = distance_lower_bound(p, light.position);
  const double len = glm::length(v);
  return {len > 0.0 ? v / len : glm::dvec3(0.0, 0.0, 1.0), 1.0 / (1.0 + r * r)};
}

std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p) {
  if (light.type != LightType::Point || !light.exact) return {light_at(light, p)};
  std::vector<LightAtPoint> out;
  try {
    const std::vector<Connection> cs = light.reach > 0.0
                                           ? geodesics_between(p, light.position, distance(p, light.position) + light.reach)
                                           : minimising_geodesics(p, light.position);
    for (const Connection& c : cs) {
      if (c.length == 0.0) continue;
      out.push_back({glm::normalize(c.direction), 1.0 / (1.0 + c.length * c.length)});
    }
  } catch (const OutOfRange&) {
    return {light_at(light, p)};  // no connection found (extreme far points): the approximate direction
  }
  return out;
}

StereoEyes stereo_eyes(const Camera& camera, double ipd) {
  if (!std::isfinite(ipd) || ipd < 0.0) {
    throw InvalidArgument("sol::stereo_eyes: ipd must be finite and >= 0, got " + std::to_string(ipd));
  }
  const CameraBasis basis = camera_basis(camera);
  const glm::dvec3 forward = basis.forward, right = basis.right, up = basis.up;
  auto eye = [&](double t) {
    // Flow along `right` by t; the frame vectors follow by parallel transport.
    const FlowTransport ft = flow_with_transport({camera.position, right}, t, FlowOptions{});
    Camera c = camera;
    c.position = ft.state.position;
    c.forward = ft.transport * forward;
    c.up = ft.transport * up;
    return c;
  };
  return {eye(-0.5 * ipd), eye(0.5 * ipd)};
}

RenderResult render_cpu_stereo(const Scene& scene, const RenderSettings& settings, double ipd) {
  const StereoEyes eyes = stereo_eyes(scene.camera, ipd);
  Scene left = scene, right = scene;
  left.camera = eyes.left;
  right.camera = eyes.right;
  const RenderResult a = render_cpu(left, settings), b = render_cpu(right, settings);
  const int w = settings.width, h = settings.height;
  RenderResult r;
  r.width = 2 * w;
  r.height = h;
  auto join = [&](const std::vector<float>& x, const std::vector<float>& y, int channels) {
    std::vector<float> out(static_cast<std::size_t>(2 * w) * h * channels);
    const std::size_t row = static_cast<std::size_t>(w) * channels;
    for (int j = 0; j < h; ++j) {
      std::copy_n(x.begin() + static_cast<std::ptrdiff_t>(j * row), row, out.begin() + static_cast<std::ptrdiff_t>(2 * j * row));
      std::copy_n(y.begin() + static_cast<std::ptrdiff_t>(j * row), row,
                  out.begin() + static_cast<std::ptrdiff_t>((2 * j + 1) * row));
    }
    return out;
  };
  r.rgba = join(a.rgba, b.rgba, 4);
  r.object = join(a.object, b.object, 1);
  r.distance = join(a.distance, b.distance, 1);
  r.px = join(a.px, b.px, 1);
  r.py = join(a.py, b.py, 1);
  r.pz = join(a.pz, b.pz, 1);
  r.steps = join(a.steps, b.steps, 1);
  return r;
}

}  // namespace sol
