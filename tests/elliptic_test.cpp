// Elliptic integrals and Jacobi functions against Boost.Math in 50-digit
// arithmetic, on a grid with m1 from 1 down to 1e-15, m from 1e-15 up, and
// arguments up to 1e4 K, in double and float.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <boost/math/special_functions/jacobi_zeta.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using Real = boost::multiprecision::cpp_bin_float_50;
namespace el = sol::elliptic;

// The parameter as the caller passes it: m and m1 both representable; the
// exact one (the smaller) defines the reference parameter.
template <class T>
struct Param {
  T m, m1;
  Real exact_m() const { return m < m1 ? Real(m) : Real(1) - Real(m1); }
};

template <class T>
std::vector<Param<T>> parameters() {
  std::vector<Param<T>> p;
  for (const double m1 : {1.0, 0.75, 0.5, 0.25, 0.1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14, 1e-15}) {
    const T m1t = static_cast<T>(m1);
    p.push_back({static_cast<T>(1) - m1t, m1t});
  }
  for (const double m : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3}) {
    const T mt = static_cast<T>(m);
    p.push_back({mt, static_cast<T>(1) - mt});
  }
  return p;
}

// Multiples of K for the arguments: small, inside each quarter, at the
// quarter points (zeros of sn and cn), and far out up to 1e4 K.
const double kFractions[] = {1e-9, 0.01,  0.3,   0.5,   0.77, 1.0,   1.23,   1.9,     2.0,    2.5,     3.0,
                             3.99, 7.5,   -0.6,  -1.0,  -2.7, 101.3, -997.0, 9999.8, 1e4,    -1e4 + 1.0};

// Relative error in units a caller can compare with the goals: for double
// the plain relative error, for float the error in ulps of the reference.
template <class T>
double error(T got, const Real& ref) {
  const double r = static_cast<double>(ref);
  if (r == 0) return got == T(0) ? 0.0 : std::numeric_limits<double>::infinity();
  const double diff = std::abs(static_cast<double>(Real(got) - ref));
  if constexpr (std::is_same_v<T, float>) {
    const float a = std::abs(static_cast<float>(r));
    return diff / (std::nextafter(a, std::numeric_limits<float>::infinity()) - a);
  } else {
    return diff / std::abs(r);
  }
}

struct Worst {
  double error = 0;
  std::string where;
  void update(double e, const std::string& w) {
    if (!(e <= error)) {  // NaN also lands here
      error = e;
      where = w;
    }
  }
};

std::string at(double m, double m1, double x) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "m = %.17g, m1 = %.3g, argument %.17g", m, m1, x);
  return buf;
}

template <class T>
struct Report {
  Worst k, e, f, einc, sn, cn, dn, am, eps, zeta;
};

template <class T>
Report<T> run_grid() {
  Report<T> rep;
  const Real pi = boost::math::constants::pi<Real>();
  for (const Param<T>& p : parameters<T>()) {
    const Real m = p.exact_m();
    const Real k = sqrt(m);
    const Real K = boost::math::ellint_1(k), E = boost::math::ellint_2(k);
    const std::string where = at(p.m, p.m1, 0);
    rep.k.update(error(el::complete_k(p.m, p.m1), K), where);
    rep.e.update(error(el::complete_e(p.m, p.m1), E), where);
    const el::Parameter<T> par = el::make_parameter(p.m, p.m1);
    // Incomplete integrals, φ in every quarter and far out.
    for (const double phi : {1e-8, 0.3, 1.0, 1.5707963, 1.5707963267948966, 1.5707963267948968, 2.5, -3.0, 4.712388980384690,
                             10.0, 100.0, -1000.5}) {
      const T x = static_cast<T>(phi);
      const Real xr = Real(x);
      rep.f.update(error(el::incomplete_f(x, p.m, p.m1), boost::math::ellint_1(k, xr)), at(p.m, p.m1, x));
      rep.einc.update(error(el::incomplete_e(x, p.m, p.m1), boost::math::ellint_2(k, xr)), at(p.m, p.m1, x));
    }
    for (const double f : kFractions) {
      const T u = static_cast<T>(f) * par.K;  // the argument as a caller forms it; the reference takes it exactly
      const Real ur = Real(u);
      Real cn_ref, dn_unused;
      const Real sn_ref = boost::math::jacobi_elliptic(k, ur, &cn_ref, &dn_unused);
      // dn from cn: dn² = m1 + m cn², every term positive (Boost's own dn is
      // a 0/0 near u = K).
      const Real dn_ref = sqrt((1 - m) + m * cn_ref * cn_ref);
      const Real h = floor(ur / (2 * K) + Real(0.5));
      // u = 2hK + v with cn v >= 0: am u = hπ + atan2(sn v, cn v), sn v = (-1)^h sn u.
      const Real sign = fmod(h, Real(2)) == 0 ? Real(1) : Real(-1);
      const Real am_ref = h * pi + atan2(sign * sn_ref, sign * cn_ref);
      const Real eps_ref = boost::math::ellint_2(k, am_ref);
      const std::string w = at(p.m, p.m1, u);
      const el::Jacobi<T> j = el::jacobi(u, par);
      rep.sn.update(error(j.sn, sn_ref), w);
      rep.cn.update(error(j.cn, cn_ref), w);
      rep.dn.update(error(j.dn, dn_ref), w);
      rep.am.update(error(el::amplitude(u, par), am_ref), w);
      rep.eps.update(error(el::epsilon(u, par), eps_ref), w);
      // Z is 2K-periodic: Boost's Z(φ) at the residual's amplitude. Measured
      // against E (its documented scale).
      const Real z_ref = boost::math::jacobi_zeta(k, atan2(sign * sn_ref, sign * cn_ref));
      EXPECT_LT(abs(z_ref - (eps_ref - E / K * ur)), Real(1e-30)) << w;  // the two references agree
      const double z_err = std::abs(static_cast<double>(Real(el::zeta(u, par)) - z_ref)) / static_cast<double>(E);
      rep.zeta.update(std::is_same_v<T, float> ? z_err / std::numeric_limits<float>::epsilon() : z_err, w);
    }
  }
  return rep;
}

template <class T>
void print(const char* name, const Report<T>& r) {
  std::printf("%s, worst error (%s) against Boost.Math at 50 digits:\n", name,
              std::is_same_v<T, float> ? "ulp" : "relative");
  const std::pair<const char*, const Worst*> rows[] = {{"K", &r.k},   {"E", &r.e},   {"F(phi)", &r.f}, {"E(phi)", &r.einc},
                                                       {"sn", &r.sn}, {"cn", &r.cn}, {"dn", &r.dn},    {"am", &r.am},
                                                       {"eps", &r.eps}, {"Z/E", &r.zeta}};
  for (const auto& [label, w] : rows) std::printf("  %-7s %.3g  (%s)\n", label, w->error, w->where.c_str());
}

template <class T>
void expect_within(const Report<T>& r, double bound) {
  for (const Worst* w : {&r.k, &r.e, &r.f, &r.einc, &r.sn, &r.cn, &r.dn, &r.am, &r.eps, &r.zeta}) {
    EXPECT_LE(w->error, bound) << w->where;
  }
}

TEST(Elliptic, DoubleMatchesBoostTo1e13) {
  const Report<double> r = run_grid<double>();
  print("double", r);
  expect_within(r, 1e-13);  // the goal for double
}

TEST(Elliptic, FloatWithin8Ulp) {
  const Report<float> r = run_grid<float>();
  print("float", r);
  expect_within(r, 8.0);  // the goal for float
}

// Exact special values and identities that hold for any parameter.
TEST(Elliptic, IdentitiesAndSpecialValues) {
  for (const Param<double>& p : parameters<double>()) {
    const el::Parameter<double> par = el::make_parameter(p.m, p.m1);
    const el::Jacobi<double> at_k = el::jacobi(par.K, par);
    EXPECT_NEAR(at_k.sn, 1.0, 1e-15);
    // cn(K) = 0 up to the rounding of K: |cn| <= k' |K - K_true| <= k' ulp(K)/2.
    EXPECT_LE(std::abs(at_k.cn), par.kc * par.K * std::numeric_limits<double>::epsilon() / 2);
    EXPECT_NEAR(at_k.dn, par.kc, 1e-15 * par.kc);
    for (const double u : {0.1, 0.7, 3.3, -12.0}) {
      const el::Jacobi<double> j = el::jacobi(u, par);
      // Each value within ~1 ulp, plus the rounding of squares and sum: 5 ulp of 1.
      EXPECT_NEAR(j.sn * j.sn + j.cn * j.cn, 1.0, 1.2e-15);
      EXPECT_NEAR(j.dn * j.dn + p.m * j.sn * j.sn, 1.0, 1.2e-15);
    }
  }
  // m = 0 and m -> 1 limits: circular and hyperbolic functions.
  const el::Jacobi<double> circ = el::jacobi(0.4, 0.0, 1.0);
  EXPECT_NEAR(circ.sn, std::sin(0.4), 1e-16);
  EXPECT_NEAR(circ.cn, std::cos(0.4), 1e-16);
  EXPECT_EQ(circ.dn, 1.0);
  const el::Jacobi<double> hyp = el::jacobi(2.0, 1.0 - 1e-300, 1e-300);
  EXPECT_NEAR(hyp.sn / std::tanh(2.0), 1.0, 1e-15);
  EXPECT_NEAR(hyp.cn * std::cosh(2.0), 1.0, 1e-15);
}

TEST(Elliptic, RejectsBadParameters) {
  EXPECT_THROW(el::make_parameter(1.0, 0.0), sol::InvalidArgument);       // K infinite
  EXPECT_THROW(el::make_parameter(0.5, 0.6), sol::InvalidArgument);       // m + m1 != 1
  EXPECT_THROW(el::make_parameter(-0.1, 1.1), sol::InvalidArgument);      // outside [0, 1]
  EXPECT_THROW(el::complete_k(std::nan(""), 0.5), sol::InvalidArgument);  // NaN
  EXPECT_THROW(el::jacobi(std::numeric_limits<double>::infinity(), 0.5, 0.5), sol::InvalidArgument);
  EXPECT_THROW(el::incomplete_f(std::nanf(""), 0.5f, 0.5f), sol::InvalidArgument);
}

}  // namespace
