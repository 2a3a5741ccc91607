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
#include "sol/error.hpp"
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

namespace {

// The primitive integer vector (k1, k2) with k1 γ1 + k2 γ2 parallel to the
// horizontal direction `heading`: the translation of Γ under which a
// horizontal line along it is invariant. The ratio of its lattice
// coordinates is found by continued fractions; InvalidArgument when no
// vector with entries below 2^20 is parallel to 1e-9.
std::array<long long, 2> lattice_period(const Lattice& lattice, const glm::dvec2& heading) {
  const glm::dvec2 sr = lattice.lattice_coordinates(heading.x, heading.y);
  const bool swapped = std::abs(sr.y) > std::abs(sr.x);
  const double big = swapped ? sr.y : sr.x, small = swapped ? sr.x : sr.y;
  const double x = small / big;  // in [-1, 1]
  long long p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  double f = x;
  for (int i = 0; i < 64; ++i) {
    const double a = std::floor(f);
    const long long p2 = static_cast<long long>(a) * p1 + p0, q2 = static_cast<long long>(a) * q1 + q0;
    p0 = p1;
    q0 = q1;
    p1 = p2;
    q1 = q2;
    if (q1 > (1LL << 20)) break;
    if (std::abs(x - static_cast<double>(p1) / static_cast<double>(q1)) <= 1e-9) {
      const long long sign = big < 0.0 ? -1 : 1;
      return swapped ? std::array<long long, 2>{sign * p1, sign * q1} : std::array<long long, 2>{sign * q1, sign * p1};
    }
    const double rest = f - a;
    if (rest <= 0.0) break;
    f = 1.0 / rest;
  }
  throw InvalidArgument("sol::quotient_images: a horizontal tube is not along a vector of the lattice ⟨γ1, γ2⟩");
}

// The words of a non-compact quotient's whose image of the anchor may come
// within `reach` of D (the proof at quotient_images, "The non-compact
// quotients"): a z loop's γ3^c of the layers (1), xy loops' γ1^a γ2^b of
// the box (2) at the anchor's own heights.
std::vector<LatticeWord> loop_words_near_domain(const Lattice& lattice, const ImageAnchor& anchor, double reach) {
  const glm::dvec3 p = anchor.point;
  std::vector<LatticeWord> words;
  if (lattice.loops() == Lattice::Loops::Z) {
    const double h = lattice.height();
    const long long c_lo = static_cast<long long>(std::ceil((-reach - p.z) / h));
    const long long c_hi = static_cast<long long>(std::floor((h + reach - p.z) / h));
    for (long long c = c_lo; c <= c_hi; ++c) words.push_back({0, 0, c});
    return words;
  }
  const glm::dvec2 g1(lattice.generators()[0]), g2(lattice.generators()[1]);
  // A point q of D within `reach` of a point of the anchor's image (at the
  // anchor's height p.z: translations keep z) has |q_z - p_z| <= reach, so
  // |Δx| <= sinh(reach) e^{q_z} <= sinh(reach) e^{p_z + reach} and |Δy| <=
  // sinh(reach) e^{reach - p_z}.
  const double wx = std::sinh(reach) * std::exp(p.z + reach), wy = std::sinh(reach) * std::exp(reach - p.z);
  double slo = std::numeric_limits<double>::infinity(), shi = -slo, rlo = slo, rhi = -slo;
  const glm::dvec2 own = lattice.lattice_coordinates(p.x, p.y);
  for (const glm::dvec2& corner : {glm::dvec2(0.0), g1, g2, g1 + g2}) {
    for (const glm::dvec2& w : {glm::dvec2(-wx, -wy), glm::dvec2(wx, -wy), glm::dvec2(-wx, wy), glm::dvec2(wx, wy)}) {
      const glm::dvec2 sr = lattice.lattice_coordinates(corner.x + w.x, corner.y + w.y) - own;
      slo = std::min(slo, sr.x);
      shi = std::max(shi, sr.x);
      rlo = std::min(rlo, sr.y);
      rhi = std::max(rhi, sr.y);
    }
  }
  if (anchor.along == ImageAnchor::Along::HorizontalLine) {
    // Within one period of the line (3), as for the compact quotients.
    const std::array<long long, 2> k = lattice_period(lattice, anchor.heading);
    slo -= static_cast<double>(std::llabs(k[0]));
    shi += static_cast<double>(std::llabs(k[0]));
    rlo -= static_cast<double>(std::llabs(k[1]));
    rhi += static_cast<double>(std::llabs(k[1]));
  }
  if ((shi - slo + 3.0) * (rhi - rlo + 3.0) > 1e6) {
    throw InvalidArgument("sol::quotient_images: over a million lattice words lie near the domain (an object far above "
                          "or below z = 0, where one of the loops is short, or loops spanning too small an area?)");
  }
  for (long long a = static_cast<long long>(std::floor(slo)) - 1; a <= static_cast<long long>(std::ceil(shi)) + 1; ++a) {
    for (long long b = static_cast<long long>(std::floor(rlo)) - 1; b <= static_cast<long long>(std::ceil(rhi)) + 1; ++b) {
      words.push_back({a, b, 0});
    }
  }
  return words;
}

// Every lattice word g = γ1^a γ2^b γ3^c whose image g·anchor may come within
// `reach` of D (the proof at quotient_images).
std::vector<LatticeWord> words_near_domain(const Lattice& lattice, const ImageAnchor& anchor, double reach) {
  if (!lattice.compact()) return loop_words_near_domain(lattice, anchor, reach);
  const double h = lattice.height();
  const glm::dvec2 g1(lattice.generators()[0]), g2(lattice.generators()[1]);
  const glm::dvec2 corners[4] = {{0.0, 0.0}, g1, g2, g1 + g2};
  double xlo = 0.0, xhi = 0.0, ylo = 0.0, yhi = 0.0;
  for (const glm::dvec2& k : corners) {
    xlo = std::min(xlo, k.x);
    xhi = std::max(xhi, k.x);
    ylo = std::min(ylo, k.y);
    yhi = std::max(yhi, k.y);
  }
  // The box B of (x, y) within `reach` of D's.
  const double wx = std::sinh(reach) * std::exp(h), wy = std::sinh(reach);
  const glm::dvec2 box[4] = {{xlo - wx, ylo - wy}, {xhi + wx, ylo - wy}, {xlo - wx, yhi + wy}, {xhi + wx, yhi + wy}};
  using Along = ImageAnchor::Along;
  const glm::dvec3 p = anchor.point;
  // Layers: the image's z is p.z + c h, within `reach` of [0, h) (a
  // vertical line through a lattice point is mapped by γ3 onto another, so
  // any one layer lists them all: these do). Every search also covers the
  // window |a|, |b| <= 22, |c| <= 2 (the golden lattice's first search,
  // which its computed ranges lie within: kept so that its images are
  // listed in the same order, and the same representative of each line
  // kept, as ever).
  constexpr long long kWindow = 22, kWindowLayers = 2;
  const long long c_lo = std::min(-kWindowLayers, static_cast<long long>(std::ceil((-reach - p.z) / h)));
  const long long c_hi = std::max(kWindowLayers, static_cast<long long>(std::floor((h + reach - p.z) / h)));
  std::vector<LatticeWord> words;
  for (long long c = c_lo; c <= c_hi; ++c) {
    if (anchor.along == Along::Height) {
      words.push_back({0, 0, c});
      continue;
    }
    // γ3^c · p = (λ^c x, λ^-c y, z + c h), both signs changed where γ3
    // turns and c is odd; γ1^a γ2^b then adds a γ1 + b γ2.
    const double sign = lattice.turns() && c % 2 != 0 ? -1.0 : 1.0;
    const double scale = std::exp(static_cast<double>(c) * h);
    const glm::dvec2 pc(sign * scale * p.x, sign * p.y / scale);
    const glm::dvec2 own = lattice.lattice_coordinates(pc.x, pc.y);
    double slo = std::numeric_limits<double>::infinity(), shi = -slo, rlo = slo, rhi = -slo;
    for (const glm::dvec2& k : box) {
      const glm::dvec2 sr = lattice.lattice_coordinates(k.x, k.y) - own;
      slo = std::min(slo, sr.x);
      shi = std::max(shi, sr.x);
      rlo = std::min(rlo, sr.y);
      rhi = std::max(rhi, sr.y);
    }
    if (anchor.along == Along::HorizontalLine) {
      // A line meeting B has a point there within one period of p's image.
      const std::array<long long, 2> k =
          lattice_period(lattice, glm::dvec2(scale * anchor.heading.x, anchor.heading.y / scale));
      const double k1 = static_cast<double>(std::llabs(k[0])), k2 = static_cast<double>(std::llabs(k[1]));
      slo -= k1;
      shi += k1;
      rlo -= k2;
      rhi += k2;
    }
    if ((shi - slo + 3.0) * (rhi - rlo + 3.0) > 1e6) {  // in double: no integer conversion can overflow
      throw InvalidArgument("sol::quotient_images: over a million lattice words lie near the domain (a fibre area too small?)");
    }
    const long long a_lo = std::min(-kWindow, static_cast<long long>(std::floor(slo)) - 1);
    const long long a_hi = std::max(kWindow, static_cast<long long>(std::ceil(shi)) + 1);
    const long long b_lo = std::min(-kWindow, static_cast<long long>(std::floor(rlo)) - 1);
    const long long b_hi = std::max(kWindow, static_cast<long long>(std::ceil(rhi)) + 1);
    for (long long a = a_lo; a <= a_hi; ++a) {
      for (long long b = b_lo; b <= b_hi; ++b) words.push_back({a, b, c});
    }
  }
  return words;
}

}  // namespace

// Why these images are all a march step can reach. A step starts at a point
// q of D and is at most max_step <= kQuotientMaxStep long, and
// object_distance is a lower bound of the distance to the drawn object; so
// an image whose bound exceeds max_step all over D is never reached, and
// each kind's least_distance_over_domain (objects.cpp) proves that for the
// images dropped here. The search is wide enough: every point of an object
// lies within kMaxQuotientRadius of its anchor (ImageAnchor: a centre, an
// axis, a height; validate checks the radius), so a reachable image has a
// point of its anchor within R = max_step + kMaxQuotientRadius of a point q
// of D. (1) Sol distance is at least the difference in z: the anchor's
// image at height p_z + c h (p_z in [0, h) once moved into D) lies within R
// of [0, h), which bounds c. A vertical line passes through a lattice point
// of ⟨γ1, γ2⟩ (validate checks it), and γ3 maps those onto each other, so
// any one layer c lists all of its images. (2) The distance from q to a point is at
// least asinh(|Δx| e^{-z_q}) and asinh(|Δy| e^{z_q}) (the planes x, y =
// const through it), so the anchor's reachable point lies within sinh(R)
// e^{h} in x and sinh(R) in y of D's (x, y) (the parallelogram P of γ1,
// γ2): in the box B. γ3^c moves p to p_c = (λ^c p_x, λ^-c p_y), and γ1^a
// γ2^b adds a γ1 + b γ2, so (a, b) lies in the lattice coordinates of B
// less p_c's, whose bounds the corners of B give. (3) A horizontal line
// along a lattice vector k (in lattice coordinates; γ3^c turns it into
// A^c k) is invariant under that translation, so its point in B is within
// one period of p_c's image under some word: the range widens by |k|.
// The ranges of a and b are widened by one more for rounding. The test
// Quotient.ImagesAreCompleteAndReachable checks that a wider enumeration
// finds nothing more, at both longest steps, for several lattices.
//
// The non-compact quotients (Lattice::Loops). A z loop's D is R² × [0, h)
// and its words are γ3^c alone: (1) bounds c as above, and every c in that
// range is listed (the anchor's x, y do not matter: D has every x, y).
// Xy loops' D is P × R and their words are γ1^a γ2^b, which keep z: a
// point q of D within R of a point of the anchor's image has |q_z - p_z| <=
// R, so by (2) that point lies within sinh(R) e^{p_z + R} in x and
// sinh(R) e^{R - p_z} in y of P (wider the farther the anchor is from z =
// 0, where one loop is short); (3) widens lines by their period. The
// kinds' least_distance_over_domain takes the same D (objects_internal.hpp,
// domain_extent). The same test covers a z loop and xy loops.
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
            for (const LatticeWord& w : words_near_domain(lattice, moved.image_anchor(), reach)) {
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
  f.quotient = world.quotient != Quotient::None;
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
  const char* more = world.quotient == Quotient::Monodromy ? ", or a larger quotient.fibre_area)"
                     : world.quotient == Quotient::XYLoops  ? ", or objects nearer z = 0, where neither loop is short)"
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

}  // namespace sol
