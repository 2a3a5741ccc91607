// The mirror material: a perfect mirror that reflects all the light along
// the reflected geodesic, coloured by the albedo (the object's colour times
// its pattern: a tinted metal; white reflects everything). No diffuse
// light. Valid C++ and GLSL, as sol/materials/lobes.h.
#ifndef SOL_MATERIALS_MIRROR_H
#define SOL_MATERIALS_MIRROR_H

#include "sol/materials/lobes.h"

#ifdef __cplusplus
namespace sol::kernel {
#endif

SOL_MATERIAL_FUNCTION SolLobes sol_mirror_lobes(SOL_VEC3 albedo, SOL_VEC4 params) {
  SOL_UNUSED(params);
  SolLobes lobes;
  lobes.diffuse = 0.0;
  lobes.specular = albedo;
  lobes.roughness = 0.0;
  lobes.ior = 0.0;
  lobes.specular_probability = 1.0;
  return lobes;
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_MIRROR_H
