// What every kind of object provides, and what it shares.
//
// A kind is a struct: its data (in Sol coordinates, directions as
// coordinate directions), and what the march needs of it, in whatever
// coordinates the object and the point are both given in:
//   kName            its "type" in scene files;
//   kSolid           a solid (balls, tubes, boxes: stepped past by their
//                    clearance, normals by the gradient of the bound,
//                    patterns in their own coordinates) or not (planes);
//   distance(q)      a signed distance: exact for planes, a lower bound for
//                    solids (sol/distance.hpp), so sphere tracing never
//                    passes through the surface;
//   clearance_terms(q, u)
//                    the terms of its bound at q along the geodesic with
//                    unit tangent u (sol/clearance.hpp), from which
//                    sol::shape_clearance and sol::shape_clearances take how
//                    far that geodesic goes before it can reach the object:
//                    at least the bound's distance, longer beside it (exact
//                    balls: the bound's ball's, which holds them, so a
//                    march steps by the larger of it and distance(q));
//   normal(q)        the unit surface normal at a hit q (frame components);
//   pattern_uv(q)    the coordinates its pattern is drawn in (planes: of
//                    the world point; solids: of q relative to the object);
//   seen_from(p)     the same object left-translated by p⁻¹ (relative to p);
//   coordinate_box() a coordinate box holding the solid (planes: the plane)
//                    for the tree of bounds (sol/bounds_tree.hpp);
//   kernel_shape()   what the GLSL kernels read of it (KernelShape);
//   visit_fields(v)  its parameters as a program's controls edit them;
// and for kinds that close up in the compact quotient (planes z = c,
// balls, tubes along γ1, γ2, γ3, boxes): into_domain,
// least_distance_over_domain, image_anchor, half_turned (its image under
// (x, y, z) -> (-x, -y, z), for lattices whose γ3 turns) and same_set
// (sol::quotient_images). Its checks and scene-file keys are free functions
// of libsol/src/objects_internal.hpp. A kind lives in its own header here
// and source in libsol/src/objects/, and is one line of SOL_OBJECT_KINDS
// (sol/object_kinds.h); docs/renderer.md "Adding a kind of object".
#pragma once

#include <array>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sol/clearance.hpp"
#include "sol/coordinate_box.hpp"
#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"

namespace sol {

class Lattice;

/// What the kernels read of an object (compute/shaders/kinds/: the kind's
/// functions take `geometry`, `heading` and `radius`; in the quotient its
/// image's record `bound`).
struct KernelShape {
  int code = 0;                   ///< kernel::kObject* (sol/object_kinds.h)
  glm::dvec4 geometry{0.0};       ///< planes (c, 0, 0, 0); balls (centre, 0); tubes (point of the axis, axis code)
  glm::dvec2 heading{0.0};        ///< horizontal tubes: the axis's unit coordinate direction
  double radius = 0.0;            ///< balls, tubes
  /// The quotient's image record of the object's bound (kernel::Image::bound),
  /// in the four words a quotient march step reads of each candidate.
  glm::dvec4 bound{0.0};
};

/// How a program's control edits a number: its step and range.
struct FieldRange {
  double speed = 0.01;
  double lo = -1e300, hi = 1e300;
};

}  // namespace sol
