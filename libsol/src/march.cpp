#include "sol/march.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "field_error.hpp"
#include "sol/patterns.h"
#include "sol/error.hpp"
#include "sol/group.hpp"
#include "sol/lattice.hpp"
#include "sol/quotient_field.hpp"
#include "sol/surface_light.h"

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
  return kernel::sol_cutout_gap_bound(pattern_code(pattern), w.x, w.y, std::exp(w.z));
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
// q of D and is at most max_step <= kQuotientMaxStep long, and
// object_distance is a lower bound of the distance to the drawn object; so
// an image whose bound exceeds max_step all over D is never reached, and
// each kind's least_distance_over_domain (objects.cpp) proves that for the
// images dropped here. The words searched are the lattice's
// (Lattice::words_near_domain, whose proof is at it in lattice.cpp): every
// word whose image of the anchor may come within max_step +
// kMaxQuotientRadius of D, since every point of an object lies within
// kMaxQuotientRadius of its anchor (ImageAnchor; validate checks the
// radius). The test Quotient.ImagesAreCompleteAndReachable checks that a
// wider enumeration finds nothing more, at both longest steps, for several
// lattices, a z loop and xy loops.
std::vector<MarchObject> quotient_images(const World& world, double max_step) {
  if (!(max_step > 0.0 && max_step <= kQuotientMaxStep)) {
    throw std::invalid_argument("sol::quotient_images: max_step must be in (0, kQuotientMaxStep]");
  }
  const std::optional<Lattice> world_lattice = world.lattice();
  if (!world_lattice) throw std::invalid_argument("sol::quotient_images: the world is Sol itself, not a quotient");
  const Lattice& lattice = *world_lattice;
  const double reach = max_step + kMaxQuotientRadius;
  std::vector<MarchObject> images;
  // A union (a chain of them) is listed part by part, each moved into D by
  // its own anchor and imaged as an object of its own of the same owner: Γ's
  // images of the union are those of its parts.
  const auto leaves = [](const Shape& shape) {
    std::vector<const Shape*> out, todo{&shape};
    while (!todo.empty()) {
      const Shape* s = todo.back();
      todo.pop_back();
      if (const Composite* c = std::get_if<Composite>(s); c && c->op == CompositeOp::Union) {
        todo.push_back(&c->parts->b);
        todo.push_back(&c->parts->a);
      } else {
        out.push_back(s);
      }
    }
    return out;
  };
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    for (const Shape* leaf : leaves(world.objects[i].shape)) std::visit(
        [&](const auto& kind) {
          using Kind = std::decay_t<decltype(kind)>;
          if constexpr (ClosesInQuotient<Kind>) {
            const Kind moved = kind.into_domain(lattice);
            // A word of odd c in a lattice that turns: its isometry turns first (Lattice::apply).
            const MarchObject base{moved, i}, turned{moved.half_turned(), i};
            for (const LatticeWord& w : lattice.words_near_domain(moved.image_anchor(), reach)) {
              const bool turns = lattice.turns() && w.c % 2 != 0;
              const MarchObject image = relative_to(turns ? turned : base, inverse(lattice.element(w)));
              if (std::get<Kind>(image.shape).least_distance_over_domain(lattice) > max_step) continue;
              if (std::none_of(images.begin(), images.end(), [&](const MarchObject& m) { return same_image(m, image); })) {
                images.push_back(image);
              }
            }
          }
        },
        *leaf);
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
  f.quotient = world.quotient() != Quotient::None;
  f.heights_only = !f.quotient;
  f.planes_xy_only = !world.objects.empty();
  // Each kind sets its feature (sol/object_kinds.h); a composite its own and its parts'.
  const auto add_kind = [&f](const Shape& shape, const auto& self) -> void {
    const int code = kernel_shape(shape).code;
#define SOL_KIND_FEATURE(Type, code_name, code_value, prefix, feature, solid) \
  if (code == kernel::code_name) f.feature = true;
    SOL_OBJECT_KINDS(SOL_KIND_FEATURE)
#undef SOL_KIND_FEATURE
    if (const Composite* c = std::get_if<Composite>(&shape)) {
      f.composites = true;
      self(c->parts->a, self);
      self(c->parts->b, self);
    }
  };
  for (const SceneObject& o : world.objects) {
    // Solids set `solids`.
    const int code = kernel_shape(o.shape).code;
    add_kind(o.shape, add_kind);
    f.solids = f.solids || is_solid(o.shape);
    const bool plane_z = code == kernel::kObjectPlaneZ;
    f.heights_only = f.heights_only && plane_z;
    f.planes_xy_only = f.planes_xy_only && (code == kernel::kObjectPlaneX || code == kernel::kObjectPlaneY);
    f.cutout = f.cutout || o.cutout;
    f.mirrors = f.mirrors || material_reflects(o);
    f.emission = f.emission || o.emission != glm::dvec3(0.0);
    f.textures = f.textures || o.texture != nullptr;
    f.cutout_gaps = f.cutout_gaps || (o.cutout && plane_z);
  }
  f.point_lights = std::any_of(world.lights.begin(), world.lights.end(),
                               [](const Light& l) { return l.type == LightType::Point; });
  f.fog = world.fog_density > 0.0;
  f.exact_lights = uses_exact_lights(world);
  f.light_reach = std::any_of(world.lights.begin(), world.lights.end(),
                              [](const Light& l) { return l.type == LightType::Point && l.exact && l.reach > 0.0; }) ||
                  std::any_of(world.objects.begin(), world.objects.end(), [](const SceneObject& o) { return o.glow_reach > 0.0; });
  f.shadows = std::any_of(world.lights.begin(), world.lights.end(), [](const Light& l) { return l.shadows; });
  return f;
}

std::string crowded_quotient_hint(const World& world) {
  const char* more = world.quotient() == Quotient::Monodromy ? ", or a larger quotient.fibre_area)"
                     : world.quotient() == Quotient::XYLoops  ? ", or objects nearer z = 0, where neither loop is short)"
                                                            : ")";
  return std::string("(fewer or smaller objects") + more;
}

MarchWorld::MarchWorld(const World& world, std::size_t listed) : m_world(world) {
  if (listed > kMostListed) throw InvalidArgument("sol::MarchWorld: the list march takes at most 64 objects");
  validate(world);
  m_features = features_of(world);
  m_lattice = world.lattice();
  if (m_lattice) {
    try {
      std::tie(m_objects, m_max_step) = listed_images(world);
      m_field = std::make_shared<const QuotientField>(m_objects, m_max_step, *m_lattice);
    } catch (const std::invalid_argument& e) {  // too many images for the field: say what helps
      throw InvalidArgument(std::string(e.what()) + " " + crowded_quotient_hint(world));
    }
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
    if (m_objects.size() > listed) {
      // (The tree's march takes neither short cut of the list's.)
      m_features.crowd = true;
      m_features.heights_only = m_features.planes_xy_only = false;
      std::vector<CoordinateBox> boxes;
      boxes.reserve(m_objects.size());
      for (const MarchObject& o : m_objects) boxes.push_back(shape_coordinate_box(o.shape));
      m_tree = std::make_shared<const BoundsTree>(boxes);
    }
  }
}

std::vector<MarchObject> MarchWorld::seen_from(const glm::dvec3& origin) const {
  std::vector<MarchObject> out;
  out.reserve(m_objects.size());
  for (const MarchObject& o : m_objects) out.push_back(relative_to(o, origin));
  return out;
}

std::vector<std::size_t> glow_target_objects(const MarchWorld& prepared) {
  const World& world = prepared.world();
  const bool quotient = prepared.features().quotient;
  const std::size_t most = prepared.features().crowd ? kListedObjects : world.objects.size();
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < world.objects.size() && out.size() < most; ++k) {
    const SceneObject& o = world.objects[k];
    if (o.emission == glm::dvec3(0.0)) continue;
    const Ball* ball = std::get_if<Ball>(&o.shape);
    const Tube* tube = std::get_if<Tube>(&o.shape);
    const bool target = (ball && ball->exact) ||
                        (!quotient && (ball || std::holds_alternative<Box>(o.shape) ||
                                       (tube && kernel::sol_tube_light_axis(tube->vertical(), tube->direction.x,
                                                                            tube->direction.y) >= 0)));
    if (target) out.push_back(k);
  }
  return out;
}

}  // namespace sol
