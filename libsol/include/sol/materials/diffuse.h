// The diffuse material (the default): a Lambertian surface of the object's
// albedo with a share m = params.x in [0, 1] of mirror reflection on top
// (SceneObject::mirror; 0: matte), uncoloured. Valid C++ and GLSL, as
// sol/materials/lobes.h.
#ifndef SOL_MATERIALS_DIFFUSE_H
#define SOL_MATERIALS_DIFFUSE_H

#include "sol/materials/lobes.h"

#ifdef __cplusplus
namespace sol::kernel {
#endif

SOL_MATERIAL_FUNCTION SolLobes sol_diffuse_lobes(SOL_VEC3 albedo, SOL_VEC4 params) {
  SOL_UNUSED(albedo);
  SolLobes lobes;
  lobes.diffuse = 1.0 - params.x;
  lobes.specular = SOL_VEC3(params.x);
  lobes.roughness = 0.0;
  lobes.ior = 0.0;
  lobes.specular_probability = params.x;
  return lobes;
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_DIFFUSE_H
