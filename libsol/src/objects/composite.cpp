#include "sol/objects/composite.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>

#include "../field_error.hpp"
#include "../objects_internal.hpp"
#include "sol/group.hpp"
#include "sol/lattice.hpp"

namespace sol {

using namespace detail;

std::string_view to_string(CompositeOp op) {
  switch (op) {
    case CompositeOp::Union:
      return "union";
    case CompositeOp::Intersection:
      return "intersection";
    case CompositeOp::Difference:
      return "difference";
  }
  return "?";
}

std::optional<CompositeOp> composite_op_named(std::string_view name) {
  for (CompositeOp op : {CompositeOp::Union, CompositeOp::Intersection, CompositeOp::Difference}) {
    if (to_string(op) == name) return op;
  }
  return std::nullopt;
}

// ---- Composite -------------------------------------------------------------

Composite::Composite()
    : parts(std::make_shared<const CompositeParts>(CompositeParts{Ball{}, Ball{{0.5, 0.0, 0.0}, 0.5, false}})) {}

Composite::Composite(CompositeOp o, const CompositeParts& p) : op(o), parts(std::make_shared<const CompositeParts>(p)) {}

namespace {

// The parts' distances at a point, and which part's term the composite's
// distance is (the active part; `turned` where it enters negated: B of a
// difference).
struct PartDistances {
  double a = 0.0, b = 0.0;
  double combined = 0.0;
  bool active_b = false;
  bool turned = false;
};

PartDistances part_distances(CompositeOp op, const CompositeParts& parts, const glm::dvec3& q) {
  PartDistances d;
  d.a = shape_distance(parts.a, q);
  d.b = shape_distance(parts.b, q);
  switch (op) {
    case CompositeOp::Union:
      d.active_b = d.b < d.a;
      d.combined = std::min(d.a, d.b);
      break;
    case CompositeOp::Intersection:
      d.active_b = d.b > d.a;
      d.combined = std::max(d.a, d.b);
      break;
    case CompositeOp::Difference:
      d.active_b = -d.b > d.a;
      d.turned = d.active_b;
      d.combined = std::max(d.a, -d.b);
      break;
  }
  return d;
}

// How far the geodesic from q goes along u (and back) before it can leave
// the part q is inside of (its distance d < 0): its faces' inside
// clearances, at least −d. An exact ball's are its bound ball's, which
// holds it, so not a bound on leaving the exact ball: its depth −d, exact.
Clearances leaving(const Shape& part, const glm::dvec3& q, const glm::dvec3& u, double d) {
  if (is_exact_ball(part)) return {-d, -d};
  const InsideClearances c = shape_inside_clearances(part, q, u);
  return {std::max(-d, c.ahead), std::max(-d, c.back)};
}

// ... before it can reach the part q is outside of (d > 0), at least d.
Clearances reaching(const Shape& part, const glm::dvec3& q, const glm::dvec3& u, double d) {
  const Clearances c = shape_clearances(part, q, u);
  return {std::max(d, c.ahead), std::max(d, c.back)};
}

Clearances least(const Clearances& x, const Clearances& y) { return {std::min(x.ahead, y.ahead), std::min(x.back, y.back)}; }
Clearances largest(const Clearances& x, const Clearances& y) {
  return {std::max(x.ahead, y.ahead), std::max(x.back, y.back)};
}

// The active part's normal at q (B's turned in a difference): the gradient of the distance.
glm::dvec3 active_normal(const PartDistances& d, const CompositeParts& parts, const glm::dvec3& q) {
  const glm::dvec3 n = shape_normal(d.active_b ? parts.b : parts.a, q);
  return d.turned ? -n : n;
}

// A part's kind's quotient functions, where it has them (every solid does).
template <class F>
auto with_closing(const Shape& part, F&& f, decltype(f(std::declval<const Ball&>())) otherwise) {
  return std::visit(
      [&](const auto& k) {
        using Kind = std::decay_t<decltype(k)>;
        if constexpr (ClosesInQuotient<Kind>) {
          return f(k);
        } else {
          return otherwise;
        }
      },
      part);
}

}  // namespace

double Composite::distance(const glm::dvec3& q) const { return part_distances(op, *parts, q).combined; }

// Each a bound on when the ray can first be in the composite: a union is
// reached no sooner than its nearer part; an intersection no sooner than
// each part it is outside of; a difference no sooner than A (q outside A)
// and than the ray leaves B (q inside B).
Clearances Composite::clearances(const glm::dvec3& q, const glm::dvec3& u) const {
  const PartDistances d = part_distances(op, *parts, q);
  const double f = std::max(d.combined, 0.0);
  Clearances c{f, f};
  if (d.combined <= 0.0) return c;
  switch (op) {
    case CompositeOp::Union:
      return least(reaching(parts->a, q, u, d.a), reaching(parts->b, q, u, d.b));
    case CompositeOp::Intersection:
      if (d.a > 0.0) c = largest(c, reaching(parts->a, q, u, d.a));
      if (d.b > 0.0) c = largest(c, reaching(parts->b, q, u, d.b));
      return c;
    case CompositeOp::Difference:
      if (d.a > 0.0) c = largest(c, reaching(parts->a, q, u, d.a));
      if (d.b < 0.0) c = largest(c, leaving(parts->b, q, u, d.b));
      return c;
  }
  return c;
}

// From inside: a union is left no sooner than each part q is inside of;
// an intersection no sooner than the first of its parts is left; a
// difference no sooner than the first of leaving A and reaching B.
InsideClearances Composite::inside_clearances(const glm::dvec3& q, const glm::dvec3& u) const {
  const PartDistances d = part_distances(op, *parts, q);
  const double depth = std::max(-d.combined, 0.0);
  Clearances c{depth, depth};
  if (d.combined < 0.0) {
    switch (op) {
      case CompositeOp::Union:
        if (d.a < 0.0) c = largest(c, leaving(parts->a, q, u, d.a));
        if (d.b < 0.0) c = largest(c, leaving(parts->b, q, u, d.b));
        break;
      case CompositeOp::Intersection:
        c = largest(c, least(leaving(parts->a, q, u, d.a), leaving(parts->b, q, u, d.b)));
        break;
      case CompositeOp::Difference:
        c = largest(c, least(leaving(parts->a, q, u, d.a), reaching(parts->b, q, u, d.b)));
        break;
    }
  }
  // The rate of the depth −d along u: the normal is the distance's gradient.
  return {c.ahead, c.back, -glm::dot(active_normal(d, *parts, q), u)};
}

glm::dvec3 Composite::normal(const glm::dvec3& q) const {
  return active_normal(part_distances(op, *parts, q), *parts, q);
}

glm::dvec2 Composite::pattern_uv(const glm::dvec3& q) const {
  const PartDistances d = part_distances(op, *parts, q);
  return shape_pattern_uv(d.active_b ? parts->b : parts->a, q, q);
}

Composite Composite::seen_from(const glm::dvec3& p) const {
  return {op, CompositeParts{shape_seen_from(parts->a, p), shape_seen_from(parts->b, p)}};
}

CoordinateBox Composite::coordinate_box() const {
  CoordinateBox box = shape_coordinate_box(parts->a);
  const CoordinateBox b = shape_coordinate_box(parts->b);
  if (op == CompositeOp::Union) box.add(b);
  if (op == CompositeOp::Intersection) {
    box.lo = glm::max(box.lo, b.lo);
    box.hi = glm::min(box.hi, b.hi);
  }
  return box;
}

// (The host puts its chain in the parts' buffer and its first index in x.)
KernelShape Composite::kernel_shape() const {
  return {.code = kernel::kObjectComposite,
          .geometry = {0.0, static_cast<double>(composite_chain(*this).size()), 0.0, 0.0}};
}

std::vector<std::pair<const Shape*, CompositeOp>> composite_chain(const Composite& c) {
  std::vector<std::pair<const Shape*, CompositeOp>> out;
  if (const Composite* a = std::get_if<Composite>(&c.parts->a)) {
    out = composite_chain(*a);
    if (out.empty()) return {};
  } else {
    out.emplace_back(&c.parts->a, CompositeOp::Union);
  }
  const Composite* b = std::get_if<Composite>(&c.parts->b);
  if (!b) {
    out.emplace_back(&c.parts->b, c.op);
    return out;
  }
  // A part b that is a chain of unions (of intersections, under an
  // intersection) joins the chain part by part, with exactly the same
  // distance: min(a, min(b, c)) = min(min(a, b), c), the same for max, and
  // max(a, −min(b, c)) = max(max(a, −b), −c) for a difference.
  const CompositeOp inner = c.op == CompositeOp::Intersection ? CompositeOp::Intersection : CompositeOp::Union;
  const std::vector<std::pair<const Shape*, CompositeOp>> tail = composite_chain(*b);
  if (tail.empty()) return {};
  for (std::size_t i = 1; i < tail.size(); ++i) {
    if (tail[i].second != inner) return {};
  }
  for (const auto& [part, op] : tail) out.emplace_back(part, c.op);
  return out;
}

// Both parts moved by the isometry that brings A's anchor into D.
Composite Composite::into_domain(const Lattice& lattice) const {
  const Teleport t = lattice.teleport(image_anchor().point);
  return (t.turned ? half_turned() : *this).seen_from(inverse(t.element));
}

double Composite::least_distance_over_domain(const Lattice& lattice) const {
  const auto least = [&](const Shape& part) {
    return with_closing(part, [&](const auto& k) { return k.least_distance_over_domain(lattice); }, 0.0);
  };
  const double a = least(parts->a);
  if (op == CompositeOp::Difference) return a;
  const double b = least(parts->b);
  return op == CompositeOp::Intersection ? std::max(a, b) : std::min(a, b);
}

ImageAnchor Composite::image_anchor() const {
  return with_closing(parts->a, [](const auto& k) { return k.image_anchor(); }, ImageAnchor{});
}

Composite Composite::half_turned() const {
  const auto turned = [](const Shape& part) {
    return with_closing(part, [](const auto& k) { return Shape(k.half_turned()); }, part);
  };
  return {op, CompositeParts{turned(parts->a), turned(parts->b)}};
}

bool Composite::same_set(const Composite& other) const {
  const auto same = [](const Shape& x, const Shape& y) {
    return std::visit(
        [](const auto& p, const auto& r) {
          using P = std::decay_t<decltype(p)>;
          if constexpr (std::is_same_v<P, std::decay_t<decltype(r)>> && ClosesInQuotient<P>) {
            return p.same_set(r);
          } else {
            return false;
          }
        },
        x, y);
  };
  return op == other.op && same(parts->a, other.parts->a) && same(parts->b, other.parts->b);
}

bool Composite::operator==(const Composite& other) const { return op == other.op && *parts == *other.parts; }

// ---- Checks and scene-file keys

namespace detail {

void check_kind(const Composite& c, const std::string& at, const Lattice* quotient) {
  // In a quotient an intersection or a difference follows the images of its
  // part a, which holds it; a union is listed part by part
  // (sol::quotient_images), so it may stand anywhere but as such a part a.
  if (const Composite* a = std::get_if<Composite>(&c.parts->a);
      quotient && c.op != CompositeOp::Union && a && a->op == CompositeOp::Union) {
    const std::string article = c.op == CompositeOp::Intersection ? "an " : "a ";
    field_error(at + ".a.type", at + ".a.type: a union as part a of " + article + std::string(c.name()) +
                                    " in a quotient: the " + std::string(c.name()) +
                                    " follows the images of its part a, which a union's parts do not share "
                                    "(write it as a union of " + std::string(c.name()) + "s)");
  }
  const auto check_part = [&](const Shape& part, const std::string& path) {
    if (!is_solid(part)) {
      field_error(path + ".type", path + " must be a solid (a ball, tube, box, union, intersection or difference), got " +
                                      std::string(kind_name(part)));
    }
    std::visit([&](const auto& kind) { check_kind(kind, path, quotient); }, part);
  };
  check_part(c.parts->a, at + ".a");
  check_part(c.parts->b, at + ".b");
}

void read_kind(Composite& c, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at,
               const Lattice* quotient) {
  const std::string what = at + " (a " + std::string(c.name()) + ")";
  r.require_known_object_keys(o, {"type", "a", "b"}, what, at);
  r.require_key(o, "a", what, "a part 'a'", at);
  r.require_key(o, "b", what, "a part 'b'", at);
  c.parts = std::make_shared<const CompositeParts>(
      CompositeParts{read_part(o["a"], r, at + ".a", quotient), read_part(o["b"], r, at + ".b", quotient)});
}

json write_kind(const Composite& c, const SceneObject&, const Lattice* quotient) {
  return {{"a", write_part(c.parts->a, quotient)}, {"b", write_part(c.parts->b, quotient)}};
}

}  // namespace detail
}  // namespace sol
