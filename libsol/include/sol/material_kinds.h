// The materials, written once. Each line of SOL_MATERIALS is one material
// as the scene file, the renderers and the panel see it:
//
//   X(Enum, code_name, code, prefix, name)
//
//   Enum       the sol::Material enumerator (sol/objects.hpp);
//   code_name  the kernels' code of the material, a constant of namespace
//              sol::kernel in C++ and a global constant in GLSL ...
//   code       ... and its value, unique;
//   prefix     its function sol_<prefix>_lobes in sol/materials/<prefix>.h,
//              shared by C++ (double) and GLSL (float), which
//              sol_material_lobes (sol/materials.h) dispatches to by code;
//   name       the scene file's "material" value (and the panel's, and the
//              Python keyword's).
//
// Every material also emits (SceneObject::emission) and has an albedo (its
// colour times its pattern); the lobes say how it scatters the light that
// reaches it (sol/materials/lobes.h). Valid C++ and GLSL (as
// sol/kernel_constants.h). docs/renderer.md "Adding a material" says what
// else a new material brings: its file and its tests.
#ifndef SOL_MATERIAL_KINDS_H
#define SOL_MATERIAL_KINDS_H

// clang-format off
#define SOL_MATERIALS(X)                                         \
  X(Diffuse, kMaterialDiffuse, 0, diffuse, "diffuse")            \
  X(Mirror,  kMaterialMirror,  1, mirror,  "mirror")            \
  X(Glossy,  kMaterialGlossy,  2, glossy,  "glossy")            \
  X(Glass,   kMaterialGlass,   3, glass,   "glass")
// clang-format on

#endif  // SOL_MATERIAL_KINDS_H
