#version 450
// The Sol ray-marcher: one invocation per pixel. The GLSL twin of libsol's
// CPU reference (libsol/src/render.cpp, documented in sol/render.hpp):
// camera-relative scene, closed-form geodesic precomputed once per ray and
// evaluated at the accumulated arc length from the ray's origin (no error
// accumulates), exact plane distances, the same shading.
//
// This file is the kernel's entry: which pass a pipeline runs (kSpecPass).
// The passes are specialisations of this one module (the host builds a
// pipeline per pass from the same SPIR-V, and the folding of the
// specialisation constants drops the other passes' code), each in
// march/passes.glsl. The rest lives in modules under march/, one concern
// each:
//   resources.glsl    specialisation constants and bindings
//   queue.glsl        the deferred passes' lists
//   camera.glsl       pixels, camera rays, the colour's output
//   objects.glsl      distances, clearances, normals, patterns of the objects
//   exact_balls.glsl  exact balls near their sphere
//   quotient.glsl     the lattice, D, the teleport, the distance field
//   plane_roots.glsl  planes x = c, y = c met as roots
//   march.glsl        the one march of every ray (camera and shadow)
//   shading.glsl      lights, shadows, colour, mirrors
//   paths.glsl        path tracing (PATH_TRACING; its paths in the shade pass)
//   passes.glsl       the march, resume and shade passes: a pixel's ray and what becomes of it
// and the geodesics themselves in sol_geodesic.glsl (the closed form),
// sol_connection.glsl and sol_spreading.glsl (exact lights and balls).
//
// Loops tested at their end. lavapipe runs a loop's body, masked, until no
// lane is left in it, and tests that at the body's end: a loop whose
// condition comes first (for, while) runs its body once more after its
// last lane has left, every lane masked. The loops whose bodies are dear
// (the march's steps and rounds, the objects of a step, the quotient's
// candidates, Newton's iterations) are written as do-while, tested at the
// end, behind an if where they may run no time: they run as often as their
// slowest lane needs (docs/renderer.md, "What lavapipe runs").
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "sol/vk/march_interface.h"
#include "sol/tone.h"
#include "sol_geodesic.glsl"
#include "march/resources.glsl"
#include "sol_connection.glsl"
#include "sol_spreading.glsl"
#include "march/queue.glsl"
#include "march/camera.glsl"
#include "march/objects.glsl"
#include "march/exact_balls.glsl"
#include "march/quotient.glsl"
#include "march/plane_roots.glsl"
#include "march/march.glsl"
#include "sol/materials.h"  // the materials' lobes, shared with libsol
#include "sol/surface_light.h"  // a glowing box's light points, shared with libsol
#include "march/random.glsl"
#include "march/shading.glsl"
#include "march/paths.glsl"
#include "sol/denoise.h"  // the luminance of the denoiser's light moment, shared with libsol
#include "march/passes.glsl"

void main() {
  if (PASS == kPassShade) {
    shade_pass();
  } else {
    march_pass();
  }
}
