#version 450
// The denoiser on the device (sol::vk::MarchRenderer::denoise): the filter
// of sol/denoise.h, step by step as sol::denoise (libsol/src/denoise.cpp)
// takes it on the host, in float. Three kinds of dispatch (push.mode):
//   0  prepare: each pixel's colour (less its emission: the host takes it
//      out before and puts it back after) divided by its albedo's modulation, its
//      noise (the mean of its 3 × 3 neighbours' of the same object own
//      variances, which the host computes from the light moment, or
//      without them their light's variance), and its distance slope;
//   1  one à-trous pass, taps push.step pixels apart, `light_in` to `light_out`;
//   2  finish: the filtered light times the modulation into `color` (alpha
//      kept), held to within the pixel's own noise of its unfiltered light
//      where push.clamp (its own noise known from kDenoiseClampSamples on).
#extension GL_GOOGLE_include_directive : require

#include "sol/denoise.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, set = 0, binding = 0) buffer Color { vec4 color[]; };              // RGBA, read and rewritten
layout(std430, set = 0, binding = 1) readonly buffer Normals { vec4 normals[]; };  // normal xyz, distance
layout(std430, set = 0, binding = 2) readonly buffer Albedos { vec4 albedos[]; };  // albedo rgb, object
layout(std430, set = 0, binding = 3) buffer Slopes { float slopes[]; };           // distance per pixel (prepare writes)
layout(std430, set = 0, binding = 4) buffer LightIn { vec4 light_in[]; };         // light rgb, its variance
layout(std430, set = 0, binding = 5) buffer LightOut { vec4 light_out[]; };
layout(std430, set = 0, binding = 6) readonly buffer Own { float own[]; };  // each pixel's own noise; < 0 unknown

layout(push_constant) uniform Push {
  int width, height, eye_width;
  int mode;
  int step;
  int clamp;  // finish: hold the filtered light to the pixel's own noise (sol_denoise_clamp)
} push;

int index_of(ivec2 p) { return p.y * push.width + p.x; }

// Whether pixel q lies in the image and in p's eye.
bool in_eye(ivec2 p, ivec2 q) {
  return q.x >= 0 && q.x < push.width && q.y >= 0 && q.y < push.height && q.x / push.eye_width == p.x / push.eye_width;
}

vec3 modulation(int k) {
  const vec4 a = albedos[k];
  return vec3(sol_denoise_modulation(a.r, a.w), sol_denoise_modulation(a.g, a.w), sol_denoise_modulation(a.b, a.w));
}

bool same(ivec2 p, ivec2 q) { return in_eye(p, q) && albedos[index_of(q)].w == albedos[index_of(p)].w; }

float z_at(ivec2 p, ivec2 q) { return same(p, q) ? normals[index_of(q)].w : 0.0; }

// A pixel's noise: its 3 × 3 neighbours' of the same object own variances'
// mean, or without them (own < 0) the variance of their light's luminance.
float noise_of(ivec2 p) {
  float sum = 0.0, squares = 0.0, count = 0.0, owns = 0.0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      const ivec2 q = p + ivec2(x, y);
      if (!same(p, q)) continue;
      const int kq = index_of(q);
      const float l = sol_denoise_luminance(color[kq].rgb / modulation(kq));
      sum += l;
      squares += l * l;
      count += 1.0;
      owns += own[kq];
    }
  }
  return own[index_of(p)] < 0.0 ? max(squares / count - (sum / count) * (sum / count), 0.0) : owns / count;
}

void prepare(ivec2 p) {
  const int k = index_of(p);
  const ivec2 dx = ivec2(1, 0), dy = ivec2(0, 1);
  const float z = normals[k].w;
  slopes[k] = max(sol_denoise_slope_along(z, z_at(p, p - dx), same(p, p - dx), z_at(p, p + dx), same(p, p + dx)),
                  sol_denoise_slope_along(z, z_at(p, p - dy), same(p, p - dy), z_at(p, p + dy), same(p, p + dy)));
  light_out[k] = vec4(color[k].rgb / modulation(k), noise_of(p));
}

// The filtered light times the modulation into the colour (alpha kept),
// held to the pixel's own noise about its unfiltered light where asked.
void finish(ivec2 p) {
  const int k = index_of(p);
  vec3 light = light_in[k].rgb;
  if (push.clamp != 0) {
    light = sol_denoise_clamp(light, color[k].rgb / modulation(k), noise_of(p));
  }
  color[k] = vec4(light * modulation(k), color[k].a);
}

void pass(ivec2 p) {
  const int k = index_of(p);
  const vec4 centre = light_in[k], guide_n = normals[k], guide_a = albedos[k];
  const float l = sol_denoise_luminance(centre.rgb), slope = slopes[k];
  vec3 sum = vec3(0.0);
  float weights = 0.0, variance = 0.0;
  for (int y = -2; y <= 2; ++y) {
    for (int x = -2; x <= 2; ++x) {
      const ivec2 q = p + push.step * ivec2(x, y);
      if (!in_eye(p, q)) continue;
      const int kq = index_of(q);
      const vec4 light = light_in[kq], n = normals[kq], a = albedos[kq];
      const float w = sol_denoise_tap(x) * sol_denoise_tap(y) *
                      sol_denoise_weight(guide_a.w, a.w, l, sol_denoise_luminance(light.rgb), centre.w, guide_n.xyz, n.xyz,
                                         guide_n.w, n.w, slope, float(push.step) * length(vec2(x, y)));
      sum += w * light.rgb;
      weights += w;
      variance += w * w * light.w;
    }
  }
  light_out[k] = vec4(sum / weights, variance / (weights * weights));
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= push.width || p.y >= push.height) return;
  if (push.mode == 0) {
    prepare(p);
  } else if (push.mode == 1) {
    pass(p);
  } else {
    finish(p);
  }
}
