// The glass material: a clear dielectric of index of refraction n =
// params.x (SceneObject::ior, in [1, 3]) that reflects or refracts all the
// light that meets it (sol_dielectric_direction: Fresnel's share reflected,
// the rest refracted by Snell's law into the solid, along whose exact
// geodesic it goes on to its far wall and out), coloured by the albedo at
// each passage of its surface (white: clear glass). No diffuse light. For
// solids only. Valid C++ and GLSL, as sol/materials/lobes.h.
#ifndef SOL_MATERIALS_GLASS_H
#define SOL_MATERIALS_GLASS_H

#include "sol/materials/lobes.h"

#ifdef __cplusplus
namespace sol::kernel {
#endif

SOL_MATERIAL_FUNCTION SolLobes sol_glass_lobes(SOL_VEC3 albedo, SOL_VEC4 params) {
  SolLobes lobes;
  lobes.diffuse = 0.0;
  lobes.specular = albedo;
  lobes.specular_probability = 1.0;
  lobes.roughness = 0.0;
  lobes.ior = params.x;
  return lobes;
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_GLASS_H
