#include "sol/march.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "field_error.hpp"
#include "sol/group.hpp"
#include "sol/lattice.hpp"
#include "sol/quotient_field.hpp"

namespace sol {

MarchObject relative_to(const MarchObject& object, const glm::dvec3& origin) {
  return {shape_seen_from(object.shape, origin), object.owner};
}

double object_distance(const MarchObject& object, const glm::dvec3& q) { return shape_distance(object.shape, q); }

double object_clearance(const MarchObject& object, const glm::dvec3& q, const glm::dvec3& u) {
  return shape_clearance(object.shape, q, u);
}

Clearances object_clearances(const MarchObject& object, const glm::dvec3& q, const glm::dvec3& u) {
  return shape_clearances(object.shape, q, u);
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

namespace {

// Whether two images are the same set (tubes: the same line).
bool same_image(const MarchObject& a, const MarchObject& b) {
  if (a.owner != b.owner || a.shape.index() != b.shape.index()) return false;
  return std::visit(
      [&](const auto& kind) {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (ClosesInQuotient<Kind>) {
          return kind.same_set(std::get<Kind>(b.shape));
        } else {
          return false;  // not in the quotient (sol::validate)
        }
      },
      a.shape);
}

}  // namespace

// Why these images are all a march step can reach. A step starts at a point
// q of D and is at most max_step <= kQuotientMaxStep (0.9) long, and
// object_distance is a lower bound of the distance to the drawn object; so
// an image whose bound exceeds max_step all over D is never reached, and
// each kind's least_distance_over_domain (objects.cpp) proves that for the
// images dropped here. The enumeration is wide enough. A reachable image has
// its centre (or a point of its axis) within R = 0.9 + 0.45 = 1.35 of a
// point q of D (radii are at most kMaxQuotientRadius, 0.45; validate checks
// it). (1) Sol distance is at least the difference in z, and |c| >= 3 moves
// an object, first moved into the cells z in [0, h), by at least 2h = 1.92
// from D: beyond R. (2) The distance from q to a point is at least
// asinh(|Δx| e^{-z_q}) and asinh(|Δy| e^{z_q}) (the planes x, y = const
// through it), so a reachable centre lies within sinh(R) e^{h} = 4.71 in x
// and sinh(R) = 1.80 in y of D's (x, y) (x in [0, φ + 1], y in [-1, φ]):
// lattice coordinates (s, r) of size below 4.1. γ3^c with |c| <= 2 moves a
// point of D to lattice coordinates of size at most 8 (the entries of
// [[2,1],[1,1]]^{±2} sum to at most 8 per row), and γ1^a γ2^b adds (a, b):
// |a|, |b| <= 13 suffice for balls and for vertical lines (which pass
// through lattice points, validate checks it, mapped by γ3 onto each
// other). A horizontal line along γ1 or γ2 is mapped by γ3^c onto a line
// along a lattice vector v with coordinates of size at most 5 and 3, under
// whose translation it is invariant; so its reachable point is within
// (5 + 3)/2 = 4 in lattice coordinates of an image of the moved axis point,
// which adds 4 to |a|, |b|: 17, and lattice_range is 22. The test
// Quotient.ImagesAreCompleteAndReachable checks that a wider enumeration
// finds nothing more, at both longest steps.
std::vector<MarchObject> quotient_images(const World& world, double max_step) {
  if (!(max_step > 0.0 && max_step <= kQuotientMaxStep)) {
    throw std::invalid_argument("sol::quotient_images: max_step must be in (0, kQuotientMaxStep]");
  }
  const std::optional<Lattice> world_lattice = world.lattice();
  if (!world_lattice) throw std::invalid_argument("sol::quotient_images: the world is Sol itself, not a quotient");
  const Lattice& lattice = *world_lattice;
  std::vector<MarchObject> images;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    std::visit(
        [&](const auto& kind) {
          using Kind = std::decay_t<decltype(kind)>;
          if constexpr (ClosesInQuotient<Kind>) {
            const MarchObject base{kind.into_domain(lattice), i};
            const int range = kind.lattice_range();
            for (int c = -2; c <= 2; ++c) {
              for (int a = -range; a <= range; ++a) {
                for (int b = -range; b <= range; ++b) {
                  const MarchObject image = relative_to(base, inverse(lattice.element(a, b, c)));
                  if (std::get<Kind>(image.shape).least_distance_over_domain(lattice) > max_step) continue;
                  if (std::none_of(images.begin(), images.end(), [&](const MarchObject& m) { return same_image(m, image); })) {
                    images.push_back(image);
                  }
                }
              }
            }
          }
        },
        world.objects[i].shape);
  }
  return images;
}

namespace {

// The images for the world's longest step, and that step: those within
// kQuotientMaxStep of D or, where they are more than
// kQuotientLongStepImages, those within kQuotientShortStep (one listing
// where the long step holds).
std::pair<std::vector<MarchObject>, double> listed_images(const World& world) {
  std::vector<MarchObject> images = quotient_images(world, kQuotientMaxStep);
  if (images.size() <= kQuotientLongStepImages) return {std::move(images), kQuotientMaxStep};
  return {quotient_images(world, kQuotientShortStep), kQuotientShortStep};
}

}  // namespace

double quotient_max_step(const World& world) { return listed_images(world).second; }

std::vector<MarchObject> quotient_images(const World& world) { return listed_images(world).first; }

MarchFeatures features_of(const World& world) {
  MarchFeatures f;
  f.quotient = world.quotient != Quotient::None;
  f.heights_only = !f.quotient;
  f.planes_xy_only = !world.objects.empty();
  for (const SceneObject& o : world.objects) {
    // Each kind sets its feature (sol/object_kinds.h); solids set `solids`.
    const int code = kernel_shape(o.shape).code;
#define SOL_KIND_FEATURE(Type, code_name, code_value, prefix, feature, solid) \
  if (code == kernel::code_name) f.feature = true;
    SOL_OBJECT_KINDS(SOL_KIND_FEATURE)
#undef SOL_KIND_FEATURE
    f.solids = f.solids || is_solid(o.shape);
    const bool plane_z = code == kernel::kObjectPlaneZ;
    f.heights_only = f.heights_only && plane_z;
    f.planes_xy_only = f.planes_xy_only && (code == kernel::kObjectPlaneX || code == kernel::kObjectPlaneY);
    f.cutout = f.cutout || o.cutout;
    f.cutout_gaps = f.cutout_gaps || (o.cutout && plane_z);
  }
  f.point_lights = std::any_of(world.lights.begin(), world.lights.end(),
                               [](const Light& l) { return l.type == LightType::Point; });
  f.fog = world.fog_density > 0.0;
  f.exact_lights = uses_exact_lights(world);
  f.light_reach = std::any_of(world.lights.begin(), world.lights.end(), [](const Light& l) {
    return l.type == LightType::Point && l.exact && l.reach > 0.0;
  });
  f.shadows = std::any_of(world.lights.begin(), world.lights.end(), [](const Light& l) { return l.shadows; });
  return f;
}

MarchWorld::MarchWorld(const World& world) : m_world(world) {
  validate(world);
  m_features = features_of(world);
  m_lattice = world.lattice();
  if (m_lattice) {
    std::tie(m_objects, m_max_step) = listed_images(world);
    m_field = std::make_shared<const QuotientField>(m_objects, m_max_step, *m_lattice);
    for (std::size_t i = 0; i < world.lights.size(); ++i) {
      try {
        m_light_images.push_back(quotient_light_images(world.lights[i], *m_lattice));
      } catch (const InvalidArgument& e) {
        const std::string at = "lights[" + std::to_string(i) + "].reach";
        detail::field_error(at, at + ": " + e.what());
      }
    }
  } else {
    for (std::size_t k = 0; k < world.objects.size(); ++k) m_objects.push_back({world.objects[k].shape, k});
  }
}

std::vector<MarchObject> MarchWorld::seen_from(const glm::dvec3& origin) const {
  std::vector<MarchObject> out;
  out.reserve(m_objects.size());
  for (const MarchObject& o : m_objects) out.push_back(relative_to(o, origin));
  return out;
}

}  // namespace sol
