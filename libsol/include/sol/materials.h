// Every material's lobes (sol/material_kinds.h), by the material's code:
// the one dispatch the CPU renderer (double) and the kernels (float) share.
// Valid C++ (namespace sol::kernel) and GLSL.
#ifndef SOL_MATERIALS_H
#define SOL_MATERIALS_H

#include "sol/material_kinds.h"
#include "sol/materials/diffuse.h"
#include "sol/materials/glass.h"
#include "sol/materials/glossy.h"
#include "sol/materials/mirror.h"

#ifdef __cplusplus
namespace sol::kernel {
#endif

// The lobes of material `material` (a kMaterial* code) of albedo `albedo`
// and parameters `params` (x: the diffuse material's mirror share, the
// glossy one's roughness, the glass one's index of refraction; yzw for
// materials to come); an unknown code is the diffuse material's.
#define SOL_MATERIAL_LOBES(Enum, code_name, code, prefix, name) \
  if (material == code_name) return sol_##prefix##_lobes(albedo, params);
SOL_MATERIAL_FUNCTION SolLobes sol_material_lobes(int material, SOL_VEC3 albedo, SOL_VEC4 params) {
  SOL_MATERIALS(SOL_MATERIAL_LOBES)
  return sol_diffuse_lobes(albedo, params);
}
#undef SOL_MATERIAL_LOBES

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_MATERIALS_H
