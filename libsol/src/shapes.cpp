#include "sol/shapes.hpp"

#include "check.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <cstdint>
#include <unordered_map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "sol/closed_form.hpp"
#include "sol/error.hpp"
#include "sol/geodesic.hpp"
#include "sol/group.hpp"

namespace sol {

double cut_time(const glm::dvec3& direction) {
  const double a = std::abs(direction.x), b = std::abs(direction.y);
  if (!(glm::length(direction) > 0.0) || !std::isfinite(a + b + direction.z)) {
    throw InvalidArgument("sol::cut_time: direction must be finite and non-zero");
  }
  // The straight lines (1, ±1, 0)/√2 have no z-oscillation to time, but are
  // the limit of the nearby periods (and conjugate at √2π).
  const glm::dvec3 u = glm::normalize(direction);
  if (std::abs(u.x) == std::abs(u.y) && u.z == 0.0) return kSmoothSphereRadius;
  return ClosedFormGeodesic<double>(u).period();
}

namespace {

void check_center(const glm::dvec3& center, const char* who) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(center[i])) throw InvalidArgument(std::string(who) + ": center must be finite");
  }
}

// The unit direction sphere as the octahedron |x| + |y| + |z| = n divided on
// its integer points and projected: symmetric under every permutation and
// sign change of the components (so the arithmetic below, written without
// preferring a component, keeps every symmetry bit for bit). Outward,
// counter-clockwise triangles.
Mesh direction_octahedron(int n) {
  Mesh mesh;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](const std::array<int, 3>& w) {
    const auto [it, fresh] = index.emplace(w, static_cast<int>(mesh.vertices.size()));
    if (fresh) mesh.vertices.push_back(glm::normalize(glm::dvec3(w[0], w[1], w[2])));
    return it->second;
  };
  for (int sx : {1, -1}) {
    for (int sy : {1, -1}) {
      for (int sz : {1, -1}) {
        // Corners A, B, C of the face, ordered counter-clockwise seen from outside.
        std::array<int, 3> a{sx, 0, 0}, b{0, sy, 0}, c{0, 0, sz};
        if (sx * sy * sz < 0) std::swap(b, c);
        auto point = [&](int i, int j) {
          const int k = n - i - j;
          return vertex({k * a[0] + i * b[0] + j * c[0], k * a[1] + i * b[1] + j * c[1], k * a[2] + i * b[2] + j * c[2]});
        };
        for (int i = 0; i < n; ++i) {
          for (int j = 0; i + j < n; ++j) {
            mesh.triangles.push_back({point(i, j), point(i + 1, j), point(i, j + 1)});
            if (i + j < n - 1) mesh.triangles.push_back({point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
          }
        }
      }
    }
  }
  return mesh;
}

// The quadrant's straight direction (sign a, sign b, 0)/√2 (the centre of
// the region where geodesics stop minimising first).
glm::dvec3 straight_of(const glm::dvec3& v) {
  const double h = std::numbers::sqrt2 / 2.0;
  return {v.x < 0.0 ? -h : h, v.y < 0.0 ? -h : h, 0.0};
}

// On the great circle from the straight direction s through v, the point at
// angle ρ from s: cos ρ s + sin ρ u.
struct Radial {
  glm::dvec3 s, u;
  double rho;  // v's angle
  glm::dvec3 at(double r) const { return std::cos(r) * s + std::sin(r) * u; }
  // Where the arc leaves s's quadrant (a = 0 or b = 0: a plane direction,
  // cut_time ∞) or reaches the vertical (at π/2 when u is vertical), the
  // first of them: cos ρ s_i + sin ρ u_i = 0 at tan ρ = -s_i/u_i.
  double exit() const {
    double first = std::numbers::pi / 2.0;
    for (int i = 0; i < 2; ++i) {
      if (u[i] * s[i] < 0.0) first = std::min(first, std::atan2(std::abs(s[i]), std::abs(u[i])));
    }
    return first;
  }
};

Radial radial_of(const glm::dvec3& v) {
  const glm::dvec3 s = straight_of(v);
  const glm::dvec3 off = v - glm::dot(v, s) * s;
  const double len = glm::length(off);
  return {s, len > 0.0 ? off / len : glm::dvec3(0.0, 0.0, 1.0), std::atan2(len, glm::dot(v, s))};
}

// The angle ρ in [lo, hi] where cut_time crosses `radius` on a radial arc
// (cut_time(at(lo)) < radius <= cut_time(at(hi))), by bisection to rounding.
double radial_crossing(const Radial& arc, double lo, double hi, double radius) {
  for (int i = 0; i < 80 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cut_time(arc.at(mid)) < radius ? lo : hi) = mid;
  }
  return hi;
}

// The direction where cut_time crosses `radius` on the chord from `in`
// (cut_time >= radius) to `out` (< radius), projected to the sphere, and
// its fraction of the chord from `in`.
glm::dvec3 chord_crossing(const glm::dvec3& in, const glm::dvec3& out, double radius, double* fraction) {
  double lo = 0.0, hi = 1.0;  // in at 0, out at 1
  for (int i = 0; i < 80 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cut_time(glm::normalize((1.0 - mid) * in + mid * out)) >= radius ? lo : hi) = mid;
  }
  *fraction = lo;
  return glm::normalize((1.0 - lo) * in + lo * out);
}

// The direction mesh of the closed ball's boundary beyond √2π: the part
// V = {v : cut_time(v) >= radius} of `dirs`, clipped on the curve
// cut_time = radius (vertices within a quarter edge of it moved onto it
// along their radial arc, so no sliver is left), with each point of that
// curve identified with its mirror (a, b, -c), which reaches the same point
// of the cut locus at the same length. Returns the directions (boundary ones
// with c >= 0) and the triangles.
Mesh clip_and_zip(Mesh dirs, double radius, int n) {
  const std::size_t count = dirs.vertices.size();
  enum State { In, On, Out };
  std::vector<State> state(count);
  for (std::size_t i = 0; i < count; ++i) state[i] = cut_time(dirs.vertices[i]) >= radius ? In : Out;
  // The rim's point on each edge between In and Out, keyed (in, out): one
  // bisection per edge (each edge is seen from both its triangles), kept for
  // the clipping below, where edges whose ends were not moved still cross.
  struct Crossing {
    glm::dvec3 direction;
    double fraction;  // from the In end
  };
  std::map<std::pair<int, int>, Crossing> rim;
  for (const auto& t : dirs.triangles) {
    for (int e = 0; e < 3; ++e) {
      int p = t[e], q = t[(e + 1) % 3];
      if (state[p] == state[q]) continue;
      if (state[p] == Out) std::swap(p, q);
      const auto [it, fresh] = rim.try_emplace({p, q});
      if (fresh) it->second.direction = chord_crossing(dirs.vertices[p], dirs.vertices[q], radius, &it->second.fraction);
    }
  }
  // Snap: a vertex whose edge crossing lies within a quarter of the edge
  // moves onto the curve along its radial arc (the same rule for every
  // vertex of a symmetric orbit, so the symmetries stay exact).
  const double h = std::numbers::pi / (2.0 * n);  // an edge's angle, about
  std::vector<char> near(count, 0);
  for (const auto& [edge, c] : rim) {
    if (c.fraction < 0.25) near[edge.first] = 1;
    if (c.fraction > 0.75) near[edge.second] = 1;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!near[i]) continue;
    const Radial arc = radial_of(dirs.vertices[i]);
    if (!(arc.rho > 0.0)) continue;  // the disc's centre itself: no arc (and a tiny disc)
    double lo = 0.0, hi = arc.rho;  // In: the crossing lies between s (√2π < radius) and v
    if (state[i] == Out) {
      lo = arc.rho;
      hi = arc.rho;
      while (hi < arc.rho + 0.5 * h && cut_time(arc.at(hi)) < radius) hi += 0.125 * h;
      if (cut_time(arc.at(hi)) < radius) continue;
    } else if (arc.rho - 0.5 * h > 0.0 && cut_time(arc.at(arc.rho - 0.5 * h)) >= radius) {
      continue;  // the curve is farther than half an edge along the arc: leave it
    }
    const double crossing_at = radial_crossing(arc, lo, hi, radius);
    if (std::abs(crossing_at - arc.rho) > 0.5 * h) continue;
    dirs.vertices[i] = arc.at(crossing_at);
    state[i] = On;
  }
  // Clip every triangle to V (Sutherland–Hodgman against cut_time >= radius:
  // keeps the orientation), sharing the crossing points of shared edges.
  Mesh out;
  std::vector<int> kept(count, -1);
  std::vector<char> boundary;
  auto keep = [&](int i) {
    if (kept[i] < 0) {
      kept[i] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(dirs.vertices[i]);
      boundary.push_back(state[i] == On);
    }
    return kept[i];
  };
  std::map<std::pair<int, int>, int> crossing;
  auto cross = [&](int in, int outside) {
    const auto [it, fresh] = crossing.emplace(std::pair(in, outside), static_cast<int>(out.vertices.size()));
    if (fresh) {
      out.vertices.push_back(rim.at({in, outside}).direction);  // neither end moved: still its crossing
      boundary.push_back(1);
    }
    return it->second;
  };
  std::vector<std::array<int, 3>> clipped;
  for (const auto& t : dirs.triangles) {
    int poly[4], m = 0;
    for (int e = 0; e < 3; ++e) {
      const int p = t[e], q = t[(e + 1) % 3];
      if (state[p] != Out) poly[m++] = keep(p);
      if (state[p] == In && state[q] == Out) poly[m++] = cross(p, q);
      if (state[p] == Out && state[q] == In) poly[m++] = cross(q, p);
    }
    if (m < 3) continue;
    if (m == 3) {
      clipped.push_back({poly[0], poly[1], poly[2]});
      continue;
    }
    // A quad: split along a diagonal that leaves no triangle with every
    // vertex fixed by the zip (on the rim or at c = 0: such a triangle and
    // its mirror would become one triangle twice, a fold), else the shorter.
    const auto& v = out.vertices;
    auto fixed = [&](int i) { return boundary[i] || v[i].z == 0.0; };
    const bool fold02 = (fixed(poly[0]) && fixed(poly[2])) && (fixed(poly[1]) || fixed(poly[3]));
    const bool fold13 = (fixed(poly[1]) && fixed(poly[3])) && (fixed(poly[0]) || fixed(poly[2]));
    const bool shorter02 = glm::length(v[poly[0]] - v[poly[2]]) <= glm::length(v[poly[1]] - v[poly[3]]);
    if (fold02 != fold13 ? fold13 : shorter02) {
      clipped.push_back({poly[0], poly[1], poly[2]});
      clipped.push_back({poly[0], poly[2], poly[3]});
    } else {
      clipped.push_back({poly[0], poly[1], poly[3]});
      clipped.push_back({poly[1], poly[2], poly[3]});
    }
  }
  // Zip: a boundary direction with c < 0 becomes its mirror's vertex.
  using Key = std::array<std::uint64_t, 3>;
  auto key = [](const glm::dvec3& v) {
    return Key{std::bit_cast<std::uint64_t>(v.x), std::bit_cast<std::uint64_t>(v.y), std::bit_cast<std::uint64_t>(std::abs(v.z))};
  };
  std::map<Key, int> upper;
  for (std::size_t i = 0; i < out.vertices.size(); ++i) {
    if (boundary[i] && out.vertices[i].z >= 0.0) upper.emplace(key(out.vertices[i]), static_cast<int>(i));
  }
  std::vector<int> remap(out.vertices.size());
  for (std::size_t i = 0; i < out.vertices.size(); ++i) {
    remap[i] = static_cast<int>(i);
    if (boundary[i] && out.vertices[i].z < 0.0) {
      const auto it = upper.find(key(out.vertices[i]));
      if (it == upper.end()) throw std::logic_error("sol::geodesic_sphere: the cut locus seam lost its symmetry (a bug)");
      remap[i] = it->second;
    }
  }
  // Zipped triangles; a triangle whose vertices are all fixed by the zip
  // meets its mirror as the same three vertices the other way round (a
  // fold of no thickness, left where the rim ends on a triangle at c = 0):
  // both go.
  std::vector<std::array<int, 3>> triangles;
  std::map<std::array<int, 3>, std::size_t> by_vertices;  // sorted vertices -> triangle
  std::vector<char> folded;
  for (const auto& t : clipped) {
    const std::array<int, 3> r{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (r[0] == r[1] || r[1] == r[2] || r[2] == r[0]) continue;
    std::array<int, 3> sorted = r;
    std::sort(sorted.begin(), sorted.end());
    const auto [it, fresh] = by_vertices.emplace(sorted, triangles.size());
    if (!fresh && !folded[it->second]) {
      folded[it->second] = 1;
      continue;
    }
    triangles.push_back(r);
    folded.push_back(0);
  }
  // Renumber the vertices still used.
  Mesh zipped;
  std::vector<int> index(out.vertices.size(), -1);
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    if (folded[k]) continue;
    std::array<int, 3> r = triangles[k];
    for (int& i : r) {
      if (index[i] < 0) {
        index[i] = static_cast<int>(zipped.vertices.size());
        zipped.vertices.push_back(out.vertices[i]);
      }
      i = index[i];
    }
    zipped.triangles.push_back(r);
  }
  return zipped;
}

}  // namespace

Mesh geodesic_sphere(const glm::dvec3& center, double radius, int subdivisions) {
  check_center(center, "sol::geodesic_sphere");
  if (!(radius > 0.0) || !(radius <= kMaxMeshedSphereRadius)) {
    throw InvalidArgument("sol::geodesic_sphere: radius must be in (0, " + std::to_string(kMaxMeshedSphereRadius) +
                          "], got " + detail::number_text(radius));
  }
  if (subdivisions < 1 || subdivisions > 512) {
    throw InvalidArgument("sol::geodesic_sphere: subdivisions must be in [1, 512], got " + std::to_string(subdivisions));
  }
  if (radius > kCoarseSphereRadius && subdivisions < kMinCoarseSubdivisions) {
    throw InvalidArgument("sol::geodesic_sphere: radius " + detail::number_text(radius) + " needs at least " +
                          std::to_string(kMinCoarseSubdivisions) + " subdivisions (coarser meshes cross themselves), got " +
                          std::to_string(subdivisions));
  }
  Mesh mesh = direction_octahedron(subdivisions);
  if (radius >= kSmoothSphereRadius) mesh = clip_and_zip(std::move(mesh), radius, subdivisions);
  try {
    for (glm::dvec3& v : mesh.vertices) v = flow({center, v}, radius).position;
  } catch (const OutOfRange&) {
    throw OutOfRange("sol::geodesic_sphere: its points overflow double (the center is too far from the origin)");
  }
  return mesh;
}

void check_polyline_points(std::size_t directions, long long segments, const char* who) {
  const double points = static_cast<double>(directions) * (static_cast<double>(segments) + 1.0);
  if (points > kMaxPolylinePoints) {
    char text[240];
    std::snprintf(text, sizeof text, "%s: %zu directions x %lld points = %.3g points; at most %.0e in one call", who,
                  directions, segments + 1, points, kMaxPolylinePoints);
    throw InvalidArgument(text);
  }
}

void check_cut_locus_points(std::size_t radii, long long samples, const char* who) {
  const double points = static_cast<double>(radii) * 4.0 * static_cast<double>(samples);
  if (points > kMaxCutLocusPoints) {
    char text[240];
    std::snprintf(text, sizeof text, "%s: %zu radii x 4 arcs x %lld samples = %.3g points; at most %.0e in one call", who,
                  radii, samples, points, kMaxCutLocusPoints);
    throw InvalidArgument(text);
  }
}

std::vector<std::vector<glm::dvec3>> geodesic_polylines(const glm::dvec3& from, const std::vector<glm::dvec3>& directions,
                                                        double length, int segments) {
  check_center(from, "sol::geodesic_polylines");
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InvalidArgument("sol::geodesic_polylines: length must be finite and > 0, got " + std::to_string(length));
  }
  if (segments < 1 || segments > 1000000) {
    throw InvalidArgument("sol::geodesic_polylines: segments must be in [1, 1000000], got " + std::to_string(segments));
  }
  check_polyline_points(directions.size(), segments, "sol::geodesic_polylines");
  std::vector<std::vector<glm::dvec3>> lines;
  for (const glm::dvec3& d : directions) {
    if (!std::isfinite(d.x + d.y + d.z) || !(glm::length(d) > 0.0)) {
      throw InvalidArgument("sol::geodesic_polylines: every direction must be finite and non-zero");
    }
    // One closed form per direction (sol::flow would set it up per point).
    const ClosedFormGeodesic<double> geodesic(glm::normalize(d));
    std::vector<glm::dvec3>& line = lines.emplace_back();
    line.reserve(static_cast<std::size_t>(segments) + 1);
    line.push_back(from);
    for (int i = 1; i <= segments; ++i) {
      const glm::dvec3 p = multiply(from, geodesic.at(length * i / segments).position);
      if (!std::isfinite(p.x + p.y + p.z)) {
        throw OutOfRange("sol::geodesic_polylines: the geodesic leaves the range of double (e^{z} overflows); shorten the length");
      }
      line.push_back(p);
    }
  }
  return lines;
}

std::vector<std::vector<glm::dvec3>> cut_locus_curves(const glm::dvec3& center, const std::vector<double>& radii, int samples) {
  check_center(center, "sol::cut_locus_curves");
  if (samples < 2 || samples > 100000) {
    throw InvalidArgument("sol::cut_locus_curves: samples must be in [2, 100000], got " + std::to_string(samples));
  }
  check_cut_locus_points(radii.size(), samples, "sol::cut_locus_curves");
  std::vector<std::vector<glm::dvec3>> curves;
  for (double r : radii) {
    if (!(r > kSmoothSphereRadius) || !(r <= kMaxMeshedSphereRadius)) {
      throw InvalidArgument("sol::cut_locus_curves: radii must be in (sqrt(2) pi, " + std::to_string(kMaxMeshedSphereRadius) +
                            "], got " + detail::number_text(r));
    }
    for (double sx : {1.0, -1.0}) {
      for (double sy : {1.0, -1.0}) {
        // Around the straight direction s, the directions at angle θ ∈ [0, π]
        // from e1 = (sx, -sy, 0)/√2 towards e3 (c >= 0: their mirrors reach
        // the same points), each on its radial arc where cut_time = r. The
        // arc leaves the quadrant (a plane direction, cut_time = ∞) before π/2.
        const double h = std::numbers::sqrt2 / 2.0;
        const glm::dvec3 s(sx * h, sy * h, 0.0), e1(sx * h, -sy * h, 0.0), e3(0.0, 0.0, 1.0);
        std::vector<glm::dvec3>& curve = curves.emplace_back();
        for (int i = 0; i < samples; ++i) {
          const double theta = std::numbers::pi * i / (samples - 1);
          const Radial arc{s, std::cos(theta) * e1 + std::sin(theta) * e3, 0.0};
          const double rho = radial_crossing(arc, 0.0, arc.exit(), r);
          curve.push_back(flow({center, arc.at(rho)}, r).position);
        }
      }
    }
  }
  return curves;
}

namespace {

// The ray o + t d (d unit) against triangle (a, b, c), Möller–Trumbore:
// t of the hit, or +infinity. Edges and corners count, with a margin of
// 1e-9 in the barycentric coordinates: a ray through a vertex shared by
// several triangles (a pole) must not slip between them by rounding.
double ray_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                    const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  constexpr double margin = 1e-9;
  if (u < -margin || u > 1.0 + margin) return std::numeric_limits<double>::infinity();
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  if (v < -margin || u + v > 1.0 + margin) return std::numeric_limits<double>::infinity();
  return glm::dot(e2, q) / det;
}

}  // namespace

namespace {

// A bounding volume hierarchy over a mesh's triangles (boxes split at the
// median of their centres along the longest axis), for rays that look for
// their first triangle within a reach: each ray visits the nodes its
// segment meets, nearer child first, and skips those beyond the nearest
// hit so far, so its cost grows with the logarithm of the triangles
// whatever their sizes (a uniform grid is quadratic for a geodesic
// sphere's triangles, which range over orders of magnitude).
class TriangleTree {
 public:
  explicit TriangleTree(const Mesh& mesh) : m_mesh(mesh), m_order(mesh.triangles.size()) {
    std::iota(m_order.begin(), m_order.end(), std::size_t{0});
    m_boxes.reserve(m_order.size());
    for (const auto& t : mesh.triangles) {
      const glm::dvec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
      // (Widened as ray_triangle's margin widens the triangle, and for rounding.)
      const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
      const glm::dvec3 pad = 1e-8 * (hi - lo) + 1e-12 * (glm::abs(lo) + glm::abs(hi)) + glm::dvec3(1e-300);
      m_boxes.push_back({lo - pad, hi + pad});
    }
    if (!m_order.empty()) build(0, m_order.size());
  }

  // The least t in (0, reach] where o + t d (d unit) meets a triangle not
  // incident to vertex `skip`, or +infinity.
  double first_hit(const glm::dvec3& o, const glm::dvec3& d, double reach, std::size_t skip) const {
    double least = std::numeric_limits<double>::infinity();
    if (m_nodes.empty()) return least;
    const glm::dvec3 inverse(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
    // Nodes to visit with where the ray enters them (taken when the node
    // was pushed): one beyond the nearest hit since found is skipped.
    std::vector<std::pair<std::size_t, double>>& stack = m_stack;
    stack.clear();
    stack.emplace_back(0, entry(m_nodes[0].box, o, inverse, reach));
    while (!stack.empty()) {
      const auto [index, at] = stack.back();
      stack.pop_back();
      if (!(at <= std::min(least, reach))) continue;  // (a miss is +infinity)
      const Node& node = m_nodes[index];
      if (node.count > 0) {
        for (std::size_t i = node.first; i < node.first + node.count; ++i) {
          const auto& t = m_mesh.triangles[m_order[i]];
          if (static_cast<std::size_t>(t[0]) == skip || static_cast<std::size_t>(t[1]) == skip ||
              static_cast<std::size_t>(t[2]) == skip) {
            continue;
          }
          const double hit = ray_triangle(o, d, m_mesh.vertices[t[0]], m_mesh.vertices[t[1]], m_mesh.vertices[t[2]]);
          if (hit > 0.0 && hit < least) least = hit;
        }
        continue;
      }
      // The nearer child on top of the stack.
      const double a = entry(m_nodes[node.first].box, o, inverse, std::min(least, reach));
      const double b = entry(m_nodes[node.second].box, o, inverse, std::min(least, reach));
      if (a <= b) {
        stack.emplace_back(node.second, b);
        stack.emplace_back(node.first, a);
      } else {
        stack.emplace_back(node.first, a);
        stack.emplace_back(node.second, b);
      }
    }
    return least <= reach ? least : std::numeric_limits<double>::infinity();
  }

 private:
  struct Box {
    glm::dvec3 lo, hi;
  };
  struct Node {
    Box box;
    std::size_t first = 0;   // a leaf's first triangle in m_order; an inner node's first child
    std::size_t second = 0;  // an inner node's second child
    std::size_t count = 0;   // a leaf's triangles; 0 for an inner node
  };

  // Where the segment o + t d, t in [0, until], enters `box` (slab test),
  // or +infinity where it misses it.
  static double entry(const Box& box, const glm::dvec3& o, const glm::dvec3& inverse, double until) {
    double t0 = 0.0, t1 = until;
    for (int axis = 0; axis < 3; ++axis) {
      double near = (box.lo[axis] - o[axis]) * inverse[axis], far = (box.hi[axis] - o[axis]) * inverse[axis];
      if (std::isnan(near) || std::isnan(far)) {  // d[axis] = 0 with o on a slab's face: inside if within it
        if (o[axis] < box.lo[axis] || o[axis] > box.hi[axis]) return std::numeric_limits<double>::infinity();
        continue;
      }
      if (near > far) std::swap(near, far);
      t0 = std::max(t0, near);
      t1 = std::min(t1, far);
      if (t0 > t1) return std::numeric_limits<double>::infinity();
    }
    return t0;
  }

  std::size_t build(std::size_t first, std::size_t end) {
    const std::size_t index = m_nodes.size();
    m_nodes.push_back({});
    Box box{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
    for (std::size_t i = first; i < end; ++i) {
      box.lo = glm::min(box.lo, m_boxes[m_order[i]].lo);
      box.hi = glm::max(box.hi, m_boxes[m_order[i]].hi);
    }
    m_nodes[index].box = box;
    constexpr std::size_t kLeaf = 4;
    if (end - first <= kLeaf) {
      m_nodes[index].first = first;
      m_nodes[index].count = end - first;
      return index;
    }
    const glm::dvec3 extent = box.hi - box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t middle = first + (end - first) / 2;
    std::nth_element(m_order.begin() + static_cast<std::ptrdiff_t>(first), m_order.begin() + static_cast<std::ptrdiff_t>(middle),
                     m_order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::size_t a, std::size_t b) {
                       return m_boxes[a].lo[axis] + m_boxes[a].hi[axis] < m_boxes[b].lo[axis] + m_boxes[b].hi[axis];
                     });
    const std::size_t left = build(first, middle);
    const std::size_t right = build(middle, end);
    m_nodes[index].first = left;
    m_nodes[index].second = right;
    return index;
  }

  const Mesh& m_mesh;
  std::vector<std::size_t> m_order;
  std::vector<Box> m_boxes;
  std::vector<Node> m_nodes;
  mutable std::vector<std::pair<std::size_t, double>> m_stack;
};

}  // namespace

std::vector<double> vertex_thickness(const Mesh& mesh, double up_to, const std::function<void(double)>& progress) {
  if (!(up_to > 0.0) || !std::isfinite(up_to)) throw InvalidArgument("sol::vertex_thickness: up_to must be finite and > 0");
  const std::size_t n = mesh.vertices.size();
  for (const auto& t : mesh.triangles) {
    for (int k : t) {
      if (k < 0 || static_cast<std::size_t>(k) >= n) throw InvalidArgument("sol::vertex_thickness: a triangle's index is outside the vertices");
    }
  }
  // Outward vertex normals: the triangles' cross products (twice their areas) summed.
  std::vector<glm::dvec3> normals(n, glm::dvec3(0.0));
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const glm::dvec3 area = glm::cross(b - a, c - a);
    for (int k : t) normals[static_cast<std::size_t>(k)] += area;
  }
  const TriangleTree tree(mesh);
  std::vector<double> thickness(n, std::numeric_limits<double>::infinity());
  if (progress) progress(0.0);
  for (std::size_t k = 0; k < n; ++k) {
    if (progress && k % 4096 == 4095) progress(static_cast<double>(k) / static_cast<double>(n));
    const double length = glm::length(normals[k]);
    if (!(length > 0.0)) continue;  // a vertex of no triangle
    thickness[k] = tree.first_hit(mesh.vertices[k], -normals[k] / length, up_to, k);
  }
  if (progress) progress(1.0);
  return thickness;
}

}  // namespace sol
