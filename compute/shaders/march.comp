#version 450
// The Sol ray-marcher: one invocation per pixel. The GLSL twin of libsol's
// CPU reference (libsol/src/render.cpp, documented in sol/render.hpp):
// camera-relative scene, closed-form geodesic precomputed once per ray and
// evaluated at the accumulated arc length from the ray's origin (no error
// accumulates), exact plane distances, the same shading.
//
// This file is the kernel's entry: which pass a pipeline runs
// (kSpecPass), the pixel of an invocation and what becomes of its ray.
// The rest lives in modules under march/, each one concern:
//   resources.glsl    specialisation constants and bindings
//   queue.glsl        the deferred passes' lists
//   camera.glsl       pixels, camera rays, the colour's output
//   objects.glsl      distances, clearances, normals, patterns of the objects
//   exact_balls.glsl  exact balls near their sphere
//   quotient.glsl     the lattice, D, the teleport, the distance field
//   plane_roots.glsl  planes x = c, y = c met as roots
//   march.glsl        the one march of every ray (camera and shadow)
//   shading.glsl      lights, shadows, colour, the shade pass
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

#include "sol/vk/march_interface.h"
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
#include "march/shading.glsl"

// The march and resume passes: a pixel's camera ray, marched (the resume
// pass goes on with a ray the march pass listed), and its colour and AOVs
// written, or its hit listed for the shade pass.
void march_pass() {
  // This dispatch's tile of the image (the whole image unless rendered in tiles).
  const ivec4 tile = params.tile;
  // The resume pass: the ray of a record of the march pass (defer_exact),
  // which goes on from where that pass left it.
  uvec4 resumed = uvec4(0u);
  ivec2 pixel;
  if (PASS == kPassResume) {
    const int slot = queue_slot();
    if (slot >= queue.resume.w) return;
    resumed = queue_records[kQueueResumeRecord * slot];
    pixel = unpack_pixel(resumed.x);
  } else {
    const ivec2 invocation = ivec2(gl_WorkGroupID.xy) * kGroupSize + group_pixel(int(gl_LocalInvocationIndex));
    if (any(greaterThanEqual(invocation, tile.zw))) return;
    pixel = tile.xy + invocation;
  }
  const int width = params.counts.y, height = params.counts.z;
  if (pixel.x >= width * params.counts.w || pixel.y >= height) return;
  const int eye = pixel.x >= width ? 1 : 0;
  const ivec2 local = ivec2(pixel.x - eye * width, pixel.y);
  // The point of the pixel this dispatch samples (the centre without anti-aliasing).
  const vec4 sample_at = params.pixel_sample;
  const bool write_aovs = WRITE_AOVS && sample_at.w != 0.0;
  const CameraRay ray = camera_ray(eye, local, width, height, sample_at);
  if (!ray.sees) {
    imageStore(color_image, pixel, output_color(accumulate(pixel, vec4(0.0, 0.0, 0.0, 1.0), sample_at.z)));
    if (write_aovs) {
      imageStore(aov_hit, pixel, vec4(0.0));
      imageStore(aov_point, pixel, vec4(0.0));
    }
    return;
  }
  // Where the march starts: in Sol relative to the eye (its camera, or an
  // ODS column's eye); in the quotient the eye's point of D (from double),
  // or the column's eye teleported into D.
  vec3 origin = ray.start;
  if (QUOTIENT) {
    origin = params.eyes[eye].camera.xyz;
    if (HAS_ODS) {
      origin = sol_translate(origin, ray.start);
      if (!in_domain(origin)) origin = teleport(origin, false);
    }
  } else {
    load_objects(eye);
  }
  const MarchHit h = march(origin, ray.direction, params.limits.x,
                           MarchResume(uintBitsToFloat(resumed.y), resumed.z, int(resumed.w)), kMarchCamera);
  if (h.deferred) {  // the rest of this ray in the resume pass
    defer_exact(pixel, h.resume.t, h.resume.passing, h.resume.step);
    return;
  }
  vec4 color = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 hit_aov = vec4(0.0, 0.0, float(h.steps), 0.0);
  vec4 point_aov = vec4(0.0);
  if (h.k >= 0) {
    const Surface f = surface_at(h);
    if (DEFER_SHADING) {
      defer_shading(pixel, h.q, h.t, f.n, h.k);
    } else {
      color = shade_hit(f.object, f.n, f.uv, h.t, h.q, eye);
    }
    hit_aov.x = float(f.object + 1);
    hit_aov.y = h.t;
    point_aov = vec4(f.world, 0.0);
  }
  // (A hit's colour comes from the shade pass.)
  if (!DEFER_SHADING || h.k < 0) imageStore(color_image, pixel, output_color(accumulate(pixel, color, sample_at.z)));
  if (write_aovs) {
    imageStore(aov_hit, pixel, hit_aov);
    imageStore(aov_point, pixel, point_aov);
  }
}

void main() {
  if (PASS == kPassShade) {
    shade_pass();
  } else {
    march_pass();
  }
}
