// How a material scatters the light that reaches its surface, as the
// renderers use it: a share of a diffuse (Lambertian) lobe of the surface's
// albedo, and the weight of a perfect specular reflection (the ray's
// tangent reflected in the normal, in the tangent space at the hit). Direct
// light shows diffuse times the surface's diffuse light and follows the
// reflected ray with weight specular; a path takes the specular lobe with
// probability specular_probability (weight specular over it) and the
// diffuse one otherwise (weight diffuse over its probability, times the
// albedo). Valid C++ (namespace sol::kernel, double) and GLSL (float).
#ifndef SOL_MATERIALS_LOBES_H
#define SOL_MATERIALS_LOBES_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
namespace sol::kernel {
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
};

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_LOBES_H
