// The numbers libsol and the GLSL kernels (compute/shaders) must agree on,
// written once. This file is valid C++ and valid GLSL: C++ sees each as an
// `inline constexpr` in namespace sol::kernel (reals as double), GLSL as a
// global `const` (reals as float). libsol's own constants are defined from
// these (Lattice::golden, ConnectionTable, the patterns of
// the CPU renderer); the kernels include this file directly or through
// sol/vk/march_interface.h (compute/include). A number that only one side
// uses does not belong here.
#ifndef SOL_KERNEL_CONSTANTS_H
#define SOL_KERNEL_CONSTANTS_H

#include "sol/material_kinds.h"
#include "sol/object_kinds.h"

#ifdef __cplusplus
#define SOL_CONSTANT(type, name, value) inline constexpr type name = value
#define SOL_REAL double
namespace sol::kernel {
using uint = unsigned int;
#else
#define SOL_CONSTANT(type, name, value) const type name = value
#define SOL_REAL float
#endif

// ---- The lattice Γ of the golden quotient (sol::Lattice::golden, docs/mathematics.md)
/// φ, the golden ratio (1 + √5)/2: γ1 = (φ, -1, 0), γ2 = (1, φ, 0).
SOL_CONSTANT(SOL_REAL, kPhi, 1.6180339887498948482);
/// The height of the fundamental domain D, the z of γ3: 2 ln φ.
SOL_CONSTANT(SOL_REAL, kLatticeHeight, 0.96242365011920689500);

// ---- The objects of a world in Sol
/// A Sol world of up to this many objects is marched through its list,
/// every object at every step (the kernel holds their records relative to
/// each eye in its uniforms); a larger one, on both devices, through its
/// tree of bounds (sol::BoundsTree, docs/renderer.md "Crowds").
SOL_CONSTANT(int, kListedObjects, 8);
/// The deepest a tree of bounds grows (sol::BoundsTree; a median split
/// halves the items, so 2^40 of them): the kernel's search holds a stack
/// of two more nodes.
SOL_CONSTANT(int, kTreeMaxDepth, 40);

// ---- The march in the quotient (docs/renderer.md "The quotient")
/// The longest march step: only the objects' images a step this long can
/// reach from D are listed (sol::quotient_images). Below kLatticeHeight,
/// so that a step from D ends at most one layer of cells above or below it
/// (the kernel's teleport relies on it).
SOL_CONSTANT(SOL_REAL, kQuotientMaxStep, 0.9);

// ---- sol::QuotientField: a distance field of a quotient world over D
/// Cells along the lattice coordinates s and r (x, y = s γ1 + r γ2) ...
SOL_CONSTANT(int, kFieldCells, 64);
/// ... and along z in [0, kLatticeHeight).
SOL_CONSTANT(int, kFieldLayers, 32);
/// A cell's candidate images, which the march evaluates at every step in
/// it: every image whose bound can be below this in the cell, and at least
/// the image nearest to the cell.
SOL_CONSTANT(SOL_REAL, kFieldNear, 0.25);
/// Candidate images per cell, 8 bits each in one word, filling the slots
/// from the lowest byte (the kernel stops at the first empty one);
/// kFieldEmpty marks an unused slot, kFieldAllImages a cell with more
/// candidates (every image is evaluated there).
SOL_CONSTANT(int, kFieldCandidates, 4);
SOL_CONSTANT(int, kFieldEmpty, 255);
SOL_CONSTANT(uint, kFieldAllImages, 0xFFFFFFFEu);
/// The most images of the objects around the domain a quotient world
/// holds, on the CPU and the kernel alike: a cell's candidates are bytes,
/// two of whose values (kFieldEmpty, and the bytes of kFieldAllImages) are
/// no image.
SOL_CONSTANT(int, kMaxQuotientImages, 254);
/// The over-relaxation of the quotient march (docs/renderer.md "The
/// quotient"): a step the cell's reach limits is proposed this many times
/// longer (at most kQuotientMaxStep) and kept only where the clearance
/// back from its end covers what the reach did not.
SOL_CONSTANT(SOL_REAL, kQuotientOverRelax, 1.6);
/// Taken off each cell's reach for the kernel's float rounding of the
/// position and the lattice coordinates (below 1e-5 a step; a ray's
/// positions by the zeta function, below 3e-5 after 20 restarts).
SOL_CONSTANT(SOL_REAL, kFieldRounding, 1e-4);

// ---- Object, pattern and light codes of the kernels' scene description
// The objects' codes: kObjectPlaneX, ..., one per line of SOL_OBJECT_KINDS.
#define SOL_KIND_CODE(Type, code_name, code, prefix, feature, solid) SOL_CONSTANT(int, code_name, code);
SOL_OBJECT_KINDS(SOL_KIND_CODE)
#undef SOL_KIND_CODE
// The materials' codes: kMaterialDiffuse, ..., one per line of SOL_MATERIALS.
#define SOL_MATERIAL_CODE(Enum, code_name, code, prefix, name) SOL_CONSTANT(int, code_name, code);
SOL_MATERIALS(SOL_MATERIAL_CODE)
#undef SOL_MATERIAL_CODE
/// A composite (sol::Composite, no line of SOL_OBJECT_KINDS: the kernels
/// draw it by its parts' kinds) as a chain ((P0 op1 P1) op2 P2) ... of
/// parts of the list's kinds: its record's geometry is (the index of P0 in
/// the parts' buffer, the number of parts, 0, 0).
SOL_CONSTANT(int, kObjectComposite, 7);
/// The most parts of a chain the kernel draws.
SOL_CONSTANT(int, kMaxCompositeParts, 8);
/// A composite's operation (sol::CompositeOp's order).
SOL_CONSTANT(int, kCompositeUnion, 0);
SOL_CONSTANT(int, kCompositeIntersection, 1);
SOL_CONSTANT(int, kCompositeDifference, 2);
/// The axis code of a vertical tube (any other code: horizontal, along its heading).
SOL_CONSTANT(int, kTubeVertical, 2);

SOL_CONSTANT(int, kPatternNone, 0);
SOL_CONSTANT(int, kPatternCircles, 1);
SOL_CONSTANT(int, kPatternChecker, 2);
/// Circles: discs of this radius about the points of the unit grid ...
SOL_CONSTANT(SOL_REAL, kCircleRadius, 0.3);
/// ... and the brightness between them.
SOL_CONSTANT(SOL_REAL, kCircleDark, 0.3);
/// Checker: the brightness of the dark squares.
SOL_CONSTANT(SOL_REAL, kCheckerDark, 0.45);
/// Balls and tubes: pattern cells per radian around them, 4/π (8 cells per turn).
SOL_CONSTANT(SOL_REAL, kPatternCellsPerRadian, 1.2732395447351626862);

SOL_CONSTANT(int, kProjectionPerspective, 0);      ///< sol::Projection, in the kernels' eyes
SOL_CONSTANT(int, kProjectionEquirectangular, 1);
SOL_CONSTANT(int, kProjectionFisheye, 2);

SOL_CONSTANT(int, kLightDirectional, 0);
SOL_CONSTANT(int, kLightPoint, 1);
SOL_CONSTANT(int, kLightExactPoint, 2);          ///< exact, inverse-square falloff
SOL_CONSTANT(int, kLightExactGeodesic, 3);       ///< exact, geodesic falloff (sol::sphere_area_density)
/// Most lights a scene holds.
SOL_CONSTANT(int, kMaxLights, 4);

/// Normals of balls and tubes: central differences of the distance with this
/// step along each frame vector.
SOL_CONSTANT(SOL_REAL, kNormalStep, 1e-3);

// ---- Exact balls
/// The kernels' exact balls step by the bound (their approach) until it is
/// below this, and then by the exact distance (Newton on the geodesic from
/// the centre) and its clearance, so hits lie on the true sphere.
SOL_CONSTANT(SOL_REAL, kExactShell, 0.025);
/// The longest step by an exact ball's clearance (its exact distance's
/// convexity along the ray, march/exact_balls.glsl's exact_ball_clearance).
SOL_CONSTANT(SOL_REAL, kExactClearanceCap, 0.5);

// ---- sol::ConnectionTable: the seeds of the kernels' connection solver
/// Connections kept per cell.
SOL_CONSTANT(int, kSeedSlots, 16);
/// Grid step in u = asinh x, v = asinh y and z.
SOL_CONSTANT(SOL_REAL, kSeedStep, 0.5);
/// u, v in [0, kSeedExtent]: x, y up to sinh 5 ≈ 74.
SOL_CONSTANT(SOL_REAL, kSeedExtent, 5.0);
/// z in [-kSeedHeight, kSeedHeight].
SOL_CONSTANT(SOL_REAL, kSeedHeight, 4.0);
/// Cells along u and v (kSeedExtent / kSeedStep) and along z (2 kSeedHeight / kSeedStep).
SOL_CONSTANT(int, kSeedCellsXY, 10);
SOL_CONSTANT(int, kSeedCellsZ, 16);

// ---- How light spreads along geodesics (sol/spreading.hpp, docs/lighting.md)
/// The float method's (and the kernel's) longest RK4 step in arc length.
SOL_CONSTANT(SOL_REAL, kSpreadingStep, 0.1);
/// The least area density J a light's irradiance I cos θ / J is divided by:
/// at a caustic (J = 0) the irradiance is at most I / kMinSpreading.
SOL_CONSTANT(SOL_REAL, kMinSpreading, 0.01);
/// Exact balls of radius below this are taken as strongly convex by a
/// path's exit search from their inner wall (the distance from the centre
/// is convex along the segment): below π/2, since Sol's sectional
/// curvatures are at most 1 and its injectivity radius is at least √2π
/// (docs/lighting.md, "Enclosures").
SOL_CONSTANT(SOL_REAL, kConvexBallRadius, 1.5);
/// Glowing tubes are infinite: next-event estimation draws points of a
/// window of them about the diffuse point's foot on the axis, of half
/// length kLightWindowBase + kLightWindowSlope h (h the point's distance
/// bound to the tube), at most kLightWindowMost (sol/surface_light.h);
/// reflection sampling finds the light from beyond it.
SOL_CONSTANT(SOL_REAL, kLightWindowBase, 1.0);
SOL_CONSTANT(SOL_REAL, kLightWindowSlope, 3.0);
SOL_CONSTANT(SOL_REAL, kLightWindowMost, 6.0);

// ---- The sRGB transfer function (IEC 61966-2-1), for 8-bit output
SOL_CONSTANT(SOL_REAL, kSrgbLinearLimit, 0.0031308);  ///< below it the curve is linear ...
SOL_CONSTANT(SOL_REAL, kSrgbLinearSlope, 12.92);      ///< ... with this slope
SOL_CONSTANT(SOL_REAL, kSrgbScale, 1.055);            ///< above: kSrgbScale v^(1/kSrgbGamma) - kSrgbOffset
SOL_CONSTANT(SOL_REAL, kSrgbOffset, 0.055);
SOL_CONSTANT(SOL_REAL, kSrgbGamma, 2.4);

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_KERNEL_CONSTANTS_H
