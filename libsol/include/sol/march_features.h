// The features of a world the march specialises to, written once. Each
// line of SOL_MARCH_FEATURES is one feature:
//
//   X(member, constant, id)
//
//   member    its flag in sol::MarchFeatures (sol/march.hpp), which
//             sol::features_of sets from the world;
//   constant  the kernels' boolean specialisation constant of the same
//             meaning (compute/shaders/march/resources.glsl declares them
//             all from this list): the compiler folds away what a world
//             does not use;
//   id        that constant's id, unique among the kernel's (the others,
//             the kernel's variant flags, are in sol/vk/march_interface.h).
//
// The host's specialisation list and its pipelines' keys
// (compute/src/march.cpp) come from the same list. Valid C++ and GLSL
// (as sol/kernel_constants.h); a new feature is one line here.
#ifndef SOL_MARCH_FEATURES_H
#define SOL_MARCH_FEATURES_H

// clang-format off
#define SOL_MARCH_FEATURES(X)                                                                               \
  X(quotient,       QUOTIENT,             6)  /* the compact quotient Γ\Sol */                                \
  X(heights_only,   HEIGHTS_ONLY,         1)  /* every object a plane z = c (not in the quotient): heights suffice */ \
  X(solids,         HAS_SOLIDS,           2)  /* balls, tubes or boxes: solids, which a step passes by their clearance */ \
  X(bound_balls,    HAS_BOUND_BALLS,      10) /* balls drawn with their distance bound */                     \
  X(exact_balls,    HAS_EXACT_BALLS,      8)  /* balls drawn as the true geodesic sphere */                   \
  X(tubes,          HAS_TUBES,            11)                                                               \
  X(boxes,          HAS_BOXES,            22)                                                               \
  X(planes_z,       HAS_PLANES_Z,         21) /* planes z = c */                                              \
  X(planes_xy,      HAS_PLANES_XY,        12) /* planes x = c or y = c */                                     \
  X(planes_xy_only, PLANES_XY_ONLY_WORLD, 16) /* every object a plane x = c or y = c: their crossing solved is the march */ \
  X(point_lights,   HAS_POINT_LIGHTS,     3)  /* point lights (any kind) */                                   \
  X(fog,            HAS_FOG,              4)                                                                \
  X(cutout,         HAS_CUTOUT,           5)  /* cutout planes */                                             \
  X(exact_lights,   HAS_EXACT_LIGHTS,     9)  /* exact point lights */                                        \
  X(light_reach,    HAS_LIGHT_REACH,      17) /* exact point lights or glowing balls with a reach: the longer connections */   \
  X(shadows,        HAS_SHADOWS,          15) /* exact point lights with shadows */ \
  X(mirrors,        HAS_MIRRORS,          43) /* mirrors: rays go on along the reflected geodesic */ \
  X(emission,       HAS_EMISSION,         44) /* glowing objects */                                           \
  X(crowd,          CROWD,                46) /* a Sol world of more than kListedObjects objects: marched through its tree of bounds */ \
  X(composites,     HAS_COMPOSITES,       23) /* unions, intersections, differences of solids (their parts' kinds set theirs) */ \
  X(textures,       HAS_TEXTURES,         50) /* image textures on objects (sol/texture.h) */
// clang-format on

#endif  // SOL_MARCH_FEATURES_H
