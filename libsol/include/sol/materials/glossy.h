// The glossy material: a rough metal that reflects all the light in a lobe
// about the reflected geodesic (sol_specular_direction: GGX microfacet
// normals of roughness r = params.x in (0, 1], SceneObject::roughness),
// coloured by the albedo (the object's colour times its pattern; white
// reflects everything). No diffuse light. r near 0 is nearly the mirror
// material, r = 1 a broad sheen. Valid C++ and GLSL, as
// sol/materials/lobes.h.
#ifndef SOL_MATERIALS_GLOSSY_H
#define SOL_MATERIALS_GLOSSY_H

#include "sol/materials/lobes.h"

#ifdef __cplusplus
namespace sol::kernel {
#endif

SOL_MATERIAL_FUNCTION SolLobes sol_glossy_lobes(SOL_VEC3 albedo, SOL_VEC4 params) {
  SolLobes lobes;
  lobes.diffuse = 0.0;
  lobes.specular = albedo;
  lobes.ior = 0.0;
  lobes.specular_probability = 1.0;
  lobes.roughness = params.x;
  return lobes;
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_GLOSSY_H
