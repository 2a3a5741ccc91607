#include "sol/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "check.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"
#include "sol/kernel_constants.h"

namespace sol {

Lattice::Lattice(const glm::dvec2& g1, const glm::dvec2& g2, double height, const Monodromy& monodromy, bool turns,
                 Loops loops)
    : m_generators{glm::dvec3(g1, 0.0), glm::dvec3(g2, 0.0), glm::dvec3(0.0, 0.0, height)},
      m_monodromy(monodromy),
      m_turns(turns),
      m_loops(loops) {
  // Inverse of the 2x2 matrix with columns g1, g2 (none for a z loop: its rows stay zero).
  if (loops == Loops::Z) return;
  const double det = g1.x * g2.y - g2.x * g1.y;
  m_coordinates_row0 = glm::dvec2(g2.y, -g2.x) / det;
  m_coordinates_row1 = glm::dvec2(-g1.y, g1.x) / det;
}

Lattice Lattice::z_loop(double height) {
  if (!(height >= 1.0 && height <= 20.0)) {
    throw InvalidArgument("sol::Lattice::z_loop: the loop's height must be in [1, 20], got " + detail::number_text(height));
  }
  return Lattice({0.0, 0.0}, {0.0, 0.0}, height, Monodromy{1, 0, 0, 1}, false, Loops::Z);
}

Lattice Lattice::xy_loops(const glm::dvec2& g1, const glm::dvec2& g2) {
  const std::string name = "sol::Lattice::xy_loops: ";
  for (const glm::dvec2& g : {g1, g2}) {
    if (!std::isfinite(g.x) || !std::isfinite(g.y) || !(std::hypot(g.x, g.y) <= 1e4)) {
      throw InvalidArgument(name + "each loop must be finite and at most 1e4 long");
    }
  }
  const double area = std::abs(g1.x * g2.y - g2.x * g1.y);
  if (!(area >= 0.01 && area <= 10000.0)) {
    throw InvalidArgument(name + "the two loops must span an area |det| in [0.01, 10000], got " + detail::number_text(area) +
                          (area == 0.0 ? " (they are parallel)" : ""));
  }
  return Lattice(g1, g2, 0.0, Monodromy{1, 0, 0, 1}, false, Loops::XY);
}

Lattice Lattice::golden() {
  // φ and 2 ln φ as the kernels have them (sol/kernel_constants.h).
  constexpr double phi = kernel::kPhi;
  return Lattice({phi, -1.0}, {1.0, phi}, kernel::kLatticeHeight, Monodromy{});
}

const Lattice& Lattice::default_axes() {
  static const Lattice golden = Lattice::golden();
  return golden;
}

std::string Monodromy::str() const {
  return "[[" + std::to_string(a) + ", " + std::to_string(b) + "], [" + std::to_string(c) + ", " + std::to_string(d) +
         "]]";
}

Lattice Lattice::from_monodromy(const Monodromy& m, std::optional<double> fibre_area) {
  const std::string name = "sol::Lattice::from_monodromy: " + m.str();
  // Entries within ±2^31, so that ad - bc and the trace are exact.
  constexpr long long kLargest = 1LL << 31;
  for (long long v : {m.a, m.b, m.c, m.d}) {
    if (v > kLargest || v < -kLargest) throw InvalidArgument(name + ": entries must lie within ±2^31");
  }
  const long long det = m.a * m.d - m.b * m.c;
  if (det != 1) throw InvalidArgument(name + " is not in SL(2, Z): its determinant is " + std::to_string(det) + ", not 1");
  const long long t = m.trace();
  if (t >= -2 && t <= 2) {
    throw InvalidArgument(name + " is not hyperbolic: its trace is " + std::to_string(t) +
                          " (|trace| must exceed 2 for an Anosov map and a Sol manifold)");
  }
  // Areas far outside this put the generators beyond what the kernel's
  // floats resolve (or the images near D beyond any count a march takes).
  if (fibre_area && !(*fibre_area >= 0.01 && *fibre_area <= 10000.0)) {
    throw InvalidArgument(name + ": the fibre area must be in [0.01, 10000]");
  }
  if (m == Monodromy{} && !fibre_area) return golden();  // today's lattice, to the bit
  if (m == Monodromy{-2, -1, -1, -1} && !fibre_area) {  // its translations, with a turning γ3
    const Lattice g = golden();
    return Lattice(glm::dvec2(g.m_generators[0]), glm::dvec2(g.m_generators[1]), g.height(), m, true);
  }
  // λ > 1 with λ + 1/λ = t; u± = (c, μ - a) for the eigenvalues μ = λ, 1/λ
  // (c != 0: an integer matrix with c = 0 and determinant 1 has trace ±2),
  // normalised by u+·e2 = 1 and u-·e1 = -1.
  // A negative trace: B = -A's eigenvectors and λ, and γ3 turns.
  const bool turns = t < 0;
  const double td = static_cast<double>(turns ? -t : t);
  const double lambda = 0.5 * (td + std::sqrt(td * td - 4.0));
  const double inv = 1.0 / lambda;
  const double a = static_cast<double>(turns ? -m.a : m.a), c = static_cast<double>(turns ? -m.c : m.c);
  const glm::dvec2 up(c / (lambda - a), 1.0);      // u+ / (λ - a)
  const glm::dvec2 um(-1.0, -(inv - a) / c);       // -u- / c
  glm::dvec2 g1(up.x, um.x), g2(up.y, um.y);
  if (fibre_area) {
    const double area = std::abs(g1.x * g2.y - g2.x * g1.y);
    const double k = std::sqrt(*fibre_area / area);
    g1 *= k;
    g2 *= k;
  }
  return Lattice(g1, g2, std::log(lambda), m, turns);
}

glm::dvec3 Lattice::apply(const LatticeWord& w, const glm::dvec3& p) const {
  const bool odd = (w.c % 2) != 0;
  return sol::multiply(element(w), m_turns && odd ? half_turn(p) : p);
}

double Lattice::fibre_area() const {
  const glm::dvec3& g1 = m_generators[0];
  const glm::dvec3& g2 = m_generators[1];
  return std::abs(g1.x * g2.y - g2.x * g1.y);
}

glm::dvec3 Lattice::element(long long n1, long long n2, long long n3) const {
  // γ1 and γ2 lie in z = 0 and commute: γ1^n1 γ2^n2 = (n1 γ1 + n2 γ2) as a translation.
  const glm::dvec3 translation = static_cast<double>(n1) * m_generators[0] + static_cast<double>(n2) * m_generators[1];
  return sol::multiply(translation, {0.0, 0.0, static_cast<double>(n3) * height()});
}

glm::dvec2 Lattice::lattice_coordinates(double x, double y) const {
  return {m_coordinates_row0.x * x + m_coordinates_row0.y * y, m_coordinates_row1.x * x + m_coordinates_row1.y * y};
}

bool Lattice::contains(const glm::dvec3& p) const {
  if (m_loops != Loops::XY && !(p.z >= 0.0 && p.z < height())) return false;
  if (m_loops == Loops::Z) return std::isfinite(p.x) && std::isfinite(p.y);
  if (!std::isfinite(p.z)) return false;
  const glm::dvec2 sr = lattice_coordinates(p.x, p.y);
  return sr.x >= 0.0 && sr.x < 1.0 && sr.y >= 0.0 && sr.y < 1.0;
}

namespace {

// a·b + c·d within ±2^62, else OutOfRange.
long long checked_sum(long long a, long long b, long long c, long long d) {
  constexpr long long limit = 1LL << 62;
  long long ab = 0, cd = 0, sum = 0;
  if (__builtin_mul_overflow(a, b, &ab) || __builtin_mul_overflow(c, d, &cd) || __builtin_add_overflow(ab, cd, &sum) ||
      sum > limit || sum < -limit) {
    throw OutOfRange("sol::LatticeWord: the lattice word's coefficients leave 2^62");
  }
  return sum;
}

}  // namespace

LatticeWord LatticeWord::operator*(const LatticeWord& v) const {
  const LatticeWord& u = *this;
  // u v = γ1^{a1} γ2^{b1} (γ3^{c1} γ1^{a2} γ2^{b2} γ3^{-c1}) γ3^{c1 + c2}; conjugation by
  // γ3 maps (a, b) to M (a, b) = (2a + b, a + b), by γ3⁻¹ to M⁻¹ (a, b) = (a - b, 2b - a).
  long long va = v.a, vb = v.b;
  for (long long k = 0; k < std::abs(u.c); ++k) {
    const long long next_a = u.c > 0 ? checked_sum(2, va, 1, vb) : checked_sum(1, va, -1, vb);
    const long long next_b = u.c > 0 ? checked_sum(1, va, 1, vb) : checked_sum(-1, va, 2, vb);
    va = next_a;
    vb = next_b;
  }
  return {checked_sum(1, u.a, 1, va), checked_sum(1, u.b, 1, vb), checked_sum(1, u.c, 1, v.c)};
}

LatticeWord Lattice::multiply(const LatticeWord& u, const LatticeWord& v) const {
  // u v = γ1^{a1} γ2^{b1} (γ3^{c1} γ1^{a2} γ2^{b2} γ3^{-c1}) γ3^{c1 + c2}; conjugation by γ3 maps the
  // word's (a, b) to A (a, b), by γ3⁻¹ to A⁻¹ (a, b), A⁻¹ = [[d, -b], [-c, a]] (determinant 1).
  const Monodromy& m = m_monodromy;
  long long va = v.a, vb = v.b;
  for (long long k = 0; k < std::abs(u.c); ++k) {
    const long long next_a = u.c > 0 ? checked_sum(m.a, va, m.b, vb) : checked_sum(m.d, va, -m.b, vb);
    const long long next_b = u.c > 0 ? checked_sum(m.c, va, m.d, vb) : checked_sum(-m.c, va, m.a, vb);
    va = next_a;
    vb = next_b;
  }
  return {checked_sum(1, u.a, 1, va), checked_sum(1, u.b, 1, vb), checked_sum(1, u.c, 1, v.c)};
}

LatticeWord Lattice::inverse(const LatticeWord& w) const {
  return multiply(LatticeWord{0, 0, -w.c}, LatticeWord{-w.a, -w.b, 0});
}

LatticeWord LatticeWord::inverse() const {
  // (γ1^a γ2^b γ3^c)⁻¹ = γ3^{-c} γ1^{-a} γ2^{-b} = (γ3^{-c} γ1^{-a} γ2^{-b} γ3^{c}) γ3^{-c}.
  return LatticeWord{0, 0, -c} * LatticeWord{-a, -b, 0};
}

std::string LatticeWord::str() const {
  const LatticeWord& u = *this;
  std::string out;
  const std::pair<const char*, long long> factors[] = {{"γ1", u.a}, {"γ2", u.b}, {"γ3", u.c}};
  for (const auto& [name, power] : factors) {
    if (power == 0) continue;
    char factor[40];
    if (power == 1) {
      std::snprintf(factor, sizeof factor, "%s%s", out.empty() ? "" : " ", name);
    } else {
      std::snprintf(factor, sizeof factor, "%s%s^%lld", out.empty() ? "" : " ", name, power);
    }
    out.append(factor);
  }
  return out.empty() ? std::string("e") : out;
}

LatticeWord Lattice::word_of(const glm::dvec3& element) const {
  // element = (a γ1 + b γ2, c h): γ1^a γ2^b lies in z = 0 and γ3^c adds c h to z only.
  const glm::dvec2 ab = lattice_coordinates(element.x, element.y);
  const double c = m_loops == Loops::XY ? 0.0 : element.z / height();
  // Beyond 2^53 double holds no exact integer (and beyond 2^63 no long
  // long): such a word could not be told, let alone map the point into D.
  constexpr double kExact = 9007199254740992.0;
  if (!(std::abs(ab.x) <= kExact && std::abs(ab.y) <= kExact && std::abs(c) <= kExact)) {
    throw OutOfRange("sol::Lattice::word_of: the element is too far from the identity for its word to be exact in double");
  }
  return {std::llround(ab.x), std::llround(ab.y), std::llround(c)};
}

namespace {

// The fractional part of v in [0, 1): v - floor(v) can round up to 1.
double fraction(double v, double& whole) {
  whole = std::floor(v);
  double f = v - whole;
  if (f >= 1.0) {
    f = 0.0;
    whole += 1.0;
  }
  return f;
}

}  // namespace

Teleport Lattice::teleport(const glm::dvec3& p) const {
  detail::require_finite(p, "sol::Lattice::teleport", "p");
  if (m_loops == Loops::XY) return teleport_translations(0.0, p.x, p.y, p.z, false);
  const double h = height();
  // 1. A power of γ3 brings z into [0, h): γ3^{-n} * p = (e^{-nh} x, e^{nh} y, z - nh).
  double n = std::floor(p.z / h);
  double z = p.z - n * h;
  if (z < 0.0) {
    n -= 1.0;
    z = p.z - n * h;
  }
  if (z >= h) {
    n += 1.0;
    z = p.z - n * h;
  }
  if (!(z >= 0.0 && z < h)) z = 0.0;  // |z| so large that nh is not exact: rounding, stay in D
  // Where γ3 turns, γ3^{-n} also turns the fibre when n is odd.
  const bool turned = m_turns && std::fmod(n, 2.0) != 0.0;
  const double scale = std::exp(-n * h);
  const double x = (turned ? -scale : scale) * p.x;
  const double y = (turned ? -p.y : p.y) / scale;
  if (!std::isfinite(x) || !std::isfinite(y)) {
    throw OutOfRange("sol::Lattice::teleport: point too far from the origin to teleport in double");
  }
  if (m_loops == Loops::Z) return {{x, y, z}, {0.0, 0.0, -n * h}, false};
  return teleport_translations(n, x, y, z, turned);
}

// Step 2 of teleport: (x, y) at height z (γ3^{-n} p) into the parallelogram.
Teleport Lattice::teleport_translations(double n, double x, double y, double z, bool turned) const {
  const double h = height();
  // 2. The commuting translations γ1, γ2 bring (x, y) into the parallelogram.
  const glm::dvec2 sr = lattice_coordinates(x, y);
  double s_whole = 0.0, r_whole = 0.0;
  double s = fraction(sr.x, s_whole);
  double r = fraction(sr.y, r_whole);
  const glm::dvec2 g1(m_generators[0]), g2(m_generators[1]);
  Teleport result;
  result.turned = turned;
  result.element = glm::dvec3(-s_whole * g1 - r_whole * g2, -n * h);
  result.point = glm::dvec3(s * g1 + r * g2, z);
  // Rounding in s*g1 + r*g2 can put a point with s or r at 0 or near 1 just
  // outside D; push the offending coordinate inward by twice its excess
  // (at least an ulp of 1) until the point is inside.
  constexpr double ulp = std::numeric_limits<double>::epsilon();
  for (int i = 0; i < 64 && !contains(result.point); ++i) {
    const glm::dvec2 c = lattice_coordinates(result.point.x, result.point.y);
    if (c.x < 0.0) s += std::max(-2.0 * c.x, ulp);
    if (c.x >= 1.0) s -= std::max(2.0 * (c.x - 1.0), ulp);
    if (c.y < 0.0) r += std::max(-2.0 * c.y, ulp);
    if (c.y >= 1.0) r -= std::max(2.0 * (c.y - 1.0), ulp);
    result.point = glm::dvec3(s * g1 + r * g2, z);
  }
  return result;
}

DomainExtent Lattice::domain_extent(double z) const {
  // Heights beyond the longest step and the largest radius, with room: a
  // bound there exceeds every step a march takes.
  constexpr double kBeyond = 4.0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (m_loops == Loops::Z) return {-inf, inf, -inf, inf, false, 0.0, height(), 16, inf};
  const glm::dvec3 g1 = m_generators[0], g2 = m_generators[1];
  DomainExtent e{0.0, 0.0, 0.0, 0.0, true, 0.0, height(), 16, inf};
  for (const glm::dvec2& k : {glm::dvec2(g1), glm::dvec2(g2), glm::dvec2(g1 + g2)}) {
    e.xlo = std::min(e.xlo, k.x);
    e.xhi = std::max(e.xhi, k.x);
    e.ylo = std::min(e.ylo, k.y);
    e.yhi = std::max(e.yhi, k.y);
  }
  if (m_loops == Loops::XY) {
    e.zlo = z - kBeyond;
    e.zhi = z + kBeyond;
    e.slabs = 32;
    e.beyond = kBeyond;
  }
  return e;
}

// ---- The images of an anchor near D (sol::quotient_images)

// Why these words are all whose image of an anchor may come within R =
// `reach` of D. sol::quotient_images asks for R = max_step +
// kMaxQuotientRadius: every point of an object lies within
// kMaxQuotientRadius of its anchor (ImageAnchor: a centre, an axis, a
// height; validate checks the radius), so an image a step of max_step from
// D can reach has a point of its anchor within R of a point q of D.
// (1) Sol distance is at least the difference in z: the anchor's
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
// kinds' least_distance_over_domain takes the same D (domain_extent). The
// same test covers a z loop and xy loops.

// The primitive integer vector (k1, k2) with k1 γ1 + k2 γ2 parallel to the
// horizontal direction `heading`: the translation of Γ under which a
// horizontal line along it is invariant. The ratio of its lattice
// coordinates is found by continued fractions; InvalidArgument when no
// vector with entries below 2^20 is parallel to 1e-9.
std::array<long long, 2> Lattice::period(const glm::dvec2& heading) const {
  const glm::dvec2 sr = lattice_coordinates(heading.x, heading.y);
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
  throw InvalidArgument("sol::Lattice::period: a horizontal tube is not along a vector of the lattice ⟨γ1, γ2⟩");
}

// The words of a non-compact quotient's whose image of the anchor may come
// within `reach` of D (the proof above, "The non-compact
// quotients"): a z loop's γ3^c of the layers (1), xy loops' γ1^a γ2^b of
// the box (2) at the anchor's own heights.
std::vector<LatticeWord> Lattice::loop_words_near_domain(const ImageAnchor& anchor, double reach) const {
  const glm::dvec3 p = anchor.point;
  std::vector<LatticeWord> words;
  if (loops() == Loops::Z) {
    const double h = height();
    const long long c_lo = static_cast<long long>(std::ceil((-reach - p.z) / h));
    const long long c_hi = static_cast<long long>(std::floor((h + reach - p.z) / h));
    for (long long c = c_lo; c <= c_hi; ++c) words.push_back({0, 0, c});
    return words;
  }
  const glm::dvec2 g1(generators()[0]), g2(generators()[1]);
  // A point q of D within `reach` of a point of the anchor's image (at the
  // anchor's height p.z: translations keep z) has |q_z - p_z| <= reach, so
  // |Δx| <= sinh(reach) e^{q_z} <= sinh(reach) e^{p_z + reach} and |Δy| <=
  // sinh(reach) e^{reach - p_z}.
  const double wx = std::sinh(reach) * std::exp(p.z + reach), wy = std::sinh(reach) * std::exp(reach - p.z);
  double slo = std::numeric_limits<double>::infinity(), shi = -slo, rlo = slo, rhi = -slo;
  const glm::dvec2 own = lattice_coordinates(p.x, p.y);
  for (const glm::dvec2& corner : {glm::dvec2(0.0), g1, g2, g1 + g2}) {
    for (const glm::dvec2& w : {glm::dvec2(-wx, -wy), glm::dvec2(wx, -wy), glm::dvec2(-wx, wy), glm::dvec2(wx, wy)}) {
      const glm::dvec2 sr = lattice_coordinates(corner.x + w.x, corner.y + w.y) - own;
      slo = std::min(slo, sr.x);
      shi = std::max(shi, sr.x);
      rlo = std::min(rlo, sr.y);
      rhi = std::max(rhi, sr.y);
    }
  }
  if (anchor.along == ImageAnchor::Along::HorizontalLine) {
    // Within one period of the line (3), as for the compact quotients.
    const std::array<long long, 2> k = period(anchor.heading);
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
// `reach` of D (the proof above).
std::vector<LatticeWord> Lattice::words_near_domain(const ImageAnchor& anchor, double reach) const {
  if (!compact()) return loop_words_near_domain(anchor, reach);
  const double h = height();
  const glm::dvec2 g1(generators()[0]), g2(generators()[1]);
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
    const double sign = turns() && c % 2 != 0 ? -1.0 : 1.0;
    const double scale = std::exp(static_cast<double>(c) * h);
    const glm::dvec2 pc(sign * scale * p.x, sign * p.y / scale);
    const glm::dvec2 own = lattice_coordinates(pc.x, pc.y);
    double slo = std::numeric_limits<double>::infinity(), shi = -slo, rlo = slo, rhi = -slo;
    for (const glm::dvec2& k : box) {
      const glm::dvec2 sr = lattice_coordinates(k.x, k.y) - own;
      slo = std::min(slo, sr.x);
      shi = std::max(shi, sr.x);
      rlo = std::min(rlo, sr.y);
      rhi = std::max(rhi, sr.y);
    }
    if (anchor.along == Along::HorizontalLine) {
      // A line meeting B has a point there within one period of p's image.
      const std::array<long long, 2> k =
          period(glm::dvec2(scale * anchor.heading.x, anchor.heading.y / scale));
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


}  // namespace sol
