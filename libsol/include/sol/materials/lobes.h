// How a material scatters the light that reaches its surface, as the
// renderers use it: a share of a diffuse (Lambertian) lobe of the surface's
// albedo, and the weight of a specular reflection: perfect (the ray's
// tangent reflected in the normal, in the tangent space at the hit), or
// with a roughness r > 0 glossy, reflected in a microfacet normal drawn
// from the GGX distribution of α = r² about the normal
// (sol_specular_direction). Direct light shows diffuse times the surface's
// diffuse light and follows one reflected ray with weight specular; a path
// takes the specular lobe with probability specular_probability (weight
// specular over it) and the diffuse one otherwise (weight diffuse over its
// probability, times the albedo). Valid C++ (namespace sol::kernel,
// double) and GLSL (float).
#ifndef SOL_MATERIALS_LOBES_H
#define SOL_MATERIALS_LOBES_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
namespace sol::kernel {
using std::abs;
using std::cos;
using std::max;
using std::min;
using std::sin;
using std::sqrt;
#define SOL_VEC3 glm::dvec3
#define SOL_VEC4 glm::dvec4
#define SOL_MATERIAL_FUNCTION inline
#define SOL_UNUSED(x) (void)(x)
#else
#define SOL_UNUSED(x)
#define SOL_VEC3 vec3
#define SOL_VEC4 vec4
#define SOL_MATERIAL_FUNCTION
#endif

struct SolLobes {
  SOL_REAL diffuse;                ///< the diffuse lobe's share, in [0, 1]
  SOL_VEC3 specular;               ///< the specular reflection's weight (0: none)
  SOL_REAL specular_probability;   ///< a path's chance of the specular lobe, in [0, 1]
  SOL_REAL roughness;              ///< the specular lobe's roughness r in [0, 1] (0: a perfect reflection)
  SOL_REAL ior;                    ///< a dielectric's index of refraction (0: none; its lobe reflects or refracts)
};

// A dielectric's lobe (glass of index of refraction `ior` in air): a ray
// of unit tangent u meeting its surface, of unit normal n facing the ray,
// from outside (`inside` false) or from within the solid, is reflected
// with the probability of the Fresnel reflectance F (the exact formula for
// unpolarised light, the mean of the s and p reflectances) and refracted
// otherwise, by Snell's law with η = n1/n2 (1/ior entering, ior leaving):
// t = η u + (η cos θi - cos θt) n; past the critical angle (sin²θt >= 1)
// it is reflected wholly. `xi` is a uniform number. The frame's components
// are orthonormal coordinates of the tangent space, so the law holds
// there as in Euclidean space: the refracted ray is the geodesic with that
// tangent. Either way all the light goes on (the lobe's weight is the
// albedo): with ior 1 nothing is reflected and the ray goes on unturned.
SOL_MATERIAL_FUNCTION SOL_VEC3 sol_dielectric_direction(SOL_VEC3 u, SOL_VEC3 n, SOL_REAL ior, bool inside, SOL_REAL xi) {
  const SOL_REAL eta = inside ? ior : 1.0 / ior;
  const SOL_REAL cos_i = min(SOL_REAL(1.0), max(SOL_REAL(0.0), -dot(u, n)));
  const SOL_REAL sin2_t = eta * eta * (1.0 - cos_i * cos_i);
  const SOL_VEC3 reflected = normalize(u + 2.0 * cos_i * n);
  if (sin2_t >= 1.0) return reflected;
  const SOL_REAL cos_t = sqrt(1.0 - sin2_t);
  const SOL_REAL rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const SOL_REAL rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const SOL_REAL fresnel = 0.5 * (rs * rs + rp * rp);
  if (xi < fresnel) return reflected;
  return normalize(eta * u + (eta * cos_i - cos_t) * n);
}

// The diffuse lobe's direction about the unit normal n, with density
// cos θ / π, from two uniform numbers xi1, xi2: a point of the unit disc
// (radius √ξ1, angle 2π ξ2) lifted to the hemisphere, in the basis (t, b,
// n) of Duff et al. 2017, which turns over where its sign flips: there at
// n_z = -1/2, away from the normals of the coordinate planes and boxes'
// faces (n_z = 0 or ±1), where the CPU's normal by differences (n_z of
// order 1e-7 either side) and the kernel's (exactly 0) would take
// different sides of a seam at 0.
SOL_MATERIAL_FUNCTION SOL_VEC3 sol_cosine_direction(SOL_VEC3 n, SOL_REAL xi1, SOL_REAL xi2) {
  const SOL_REAL sign = n.z >= -0.5 ? 1.0 : -1.0;
  const SOL_REAL a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  const SOL_VEC3 t = SOL_VEC3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  const SOL_VEC3 b = SOL_VEC3(c, sign + n.y * n.y * a, -n.y);
  const SOL_REAL r = sqrt(xi1), phi = 6.28318530717958647692 * xi2;
  const SOL_REAL x = r * cos(phi), y = r * sin(phi);
  return normalize(x * t + y * b + sqrt(max(SOL_REAL(0.0), 1.0 - x * x - y * y)) * n);
}

// The specular lobe's direction for a ray of unit tangent u meeting a
// surface of unit normal n (facing the ray) with roughness r, from two
// uniform numbers xi (a path's next two; r = 0 takes none: the mirror's
// reflection u - 2 (u.n) n). A microfacet normal m is drawn from the GGX
// (Trowbridge-Reitz) distribution of α = r² with density D(m) (m.n), cos²
// θ_m = (1 - ξ1) / (1 + (α² - 1) ξ1), φ = 2π ξ2 about n (from the ray's
// tangential part), and u is
// reflected in it; a reflection that leaves below the surface is folded
// back above it (mirrored in the tangent plane), so that the lobe keeps all
// its light: its weight is the albedo alone, and a white glossy furnace
// holds E / (1 - ρ) as a diffuse one does. The frame's components are
// orthonormal coordinates of the tangent space, so the Euclidean
// construction holds there.
SOL_MATERIAL_FUNCTION SOL_VEC3 sol_specular_direction(SOL_VEC3 u, SOL_VEC3 n, SOL_REAL r, SOL_REAL xi1, SOL_REAL xi2) {
  if (r <= 0.0) return normalize(u - 2.0 * dot(u, n) * n);
  const SOL_REAL alpha2 = r * r * r * r;
  const SOL_REAL cos2 = (1.0 - xi1) / (1.0 + (alpha2 - 1.0) * xi1);
  const SOL_REAL cos_t = sqrt(cos2), sin_t = sqrt(max(SOL_REAL(0.0), 1.0 - cos2));
  const SOL_REAL phi = 6.28318530717958647692 * xi2;
  // The basis (t, b, n): t along the ray's part in the tangent plane, so
  // that it varies smoothly with n and u (a basis of n alone turns over
  // somewhere, and float and double would take different sides of that
  // seam on a vertical plane); at normal incidence any t.
  SOL_VEC3 t = u - dot(u, n) * n;
  const SOL_REAL along = length(t);
  if (along > 1e-6) {
    t = t / along;
  } else {
    t = normalize(abs(n.x) < 0.9 ? SOL_VEC3(1.0 - n.x * n.x, -n.x * n.y, -n.x * n.z)
                                 : SOL_VEC3(-n.y * n.x, 1.0 - n.y * n.y, -n.y * n.z));
  }
  const SOL_VEC3 b = cross(n, t);
  const SOL_VEC3 m = sin_t * cos(phi) * t + sin_t * sin(phi) * b + cos_t * n;
  SOL_VEC3 reflected = u - 2.0 * dot(u, m) * m;
  if (dot(reflected, n) < 0.0) reflected = reflected - 2.0 * dot(reflected, n) * n;
  return normalize(reflected);
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_LOBES_H
