// The kinds of object the march draws, written once. Each line of
// SOL_OBJECT_KINDS is one kind as the kernels see it:
//
//   X(Type, code_name, code, prefix, feature, solid)
//
//   Type       the C++ struct of the scene's object (sol/objects/*.hpp),
//              an alternative of sol::Shape; a struct may be drawn as more
//              than one kind (a Ball as a bound ball or an exact one: its
//              kernel_shape() says which);
//   code_name  the kernels' code of the kind, a constant of namespace
//              sol::kernel in C++ and a global constant in GLSL ...
//   code       ... and its value, unique;
//   prefix     the kind's GLSL functions, prefix_distance, _clearances,
//              _record_clearances, _normal and _pattern_uv, in
//              compute/shaders/kinds/<file>.glsl: march/objects.glsl
//              dispatches to them by code, so a kind listed here without
//              them does not compile;
//   feature    the sol::MarchFeatures flag (sol/march_features.h) that a
//              world with this kind sets (sol::features_of) and whose
//              specialisation constant compiles the kind into a kernel;
//   solid      whether it is a solid (balls, tubes, boxes), which the march
//              passes by its clearance along the ray, normals by the
//              gradient of its bound, and patterns in coordinates of its
//              own (Type::kSolid must agree; a static_assert checks it).
//
// C++ generates from it sol::Shape, the codes and sol::features_of; GLSL the
// codes and the kernel's dispatch. Valid C++ and GLSL (as
// sol/kernel_constants.h). docs/renderer.md "Adding a kind of object" says
// what else a new kind brings: its files and its tests.
#ifndef SOL_OBJECT_KINDS_H
#define SOL_OBJECT_KINDS_H

// clang-format off
#define SOL_OBJECT_KINDS(X)                                                  \
  X(PlaneX, kObjectPlaneX,    0, plane_x,    planes_xy,   false)              \
  X(PlaneY, kObjectPlaneY,    1, plane_y,    planes_xy,   false)              \
  X(PlaneZ, kObjectPlaneZ,    2, plane_z,    planes_z,    false)              \
  X(Ball,   kObjectBall,      3, ball,       bound_balls, true)               \
  X(Tube,   kObjectTube,      4, tube,       tubes,       true)               \
  X(Ball,   kObjectExactBall, 5, exact_ball, exact_balls, true)               \
  X(Box,    kObjectBox,       6, box,        boxes,       true)
// clang-format on

#endif  // SOL_OBJECT_KINDS_H
