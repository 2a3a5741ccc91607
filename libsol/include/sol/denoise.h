// The denoiser's numbers and weights, written once for the CPU (sol::denoise,
// sol/denoise.hpp) and the kernel (compute/shaders/denoise.comp): an
// edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika, Lensch,
// "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination
// Filtering", HPG 2010) whose edges are those of the AOVs (the albedo, the
// normal, the distance and the object of each pixel's camera ray) and of
// the colour itself, measured against the colour's own noise (as the
// luminance weight of Schied et al.'s SVGF, HPG 2017: each pixel's own
// sample variance averaged over its neighbours where it has two samples or
// more, else the spatial variance, a still having no earlier frames).
//
// The filter works on the light that reaches the surfaces: the colour less
// the emission, divided by the albedo, both the means over the pixel's
// samples (so that a pixel whose samples straddle a pattern's edge, or a
// glowing and a dark object, is divided by what its samples saw), and put
// back after; a checker or a coloured object's edge keeps its sharpness.
// kDenoisePasses passes of a 5 × 5 B3-spline kernel whose taps lie 1, 2,
// 4, ... pixels apart; from kDenoiseClampSamples samples on, the result
// held to the pixel's own noise about its unfiltered light.
// docs/lighting.md ("Denoising") derives the weights. Valid C++ (namespace
// sol::kernel, double) and GLSL (float), as sol/tone.h.
#ifndef SOL_DENOISE_H
#define SOL_DENOISE_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
namespace sol::kernel {
using glm::dot;
using std::abs;
using std::sqrt;
#define SOL_DENOISE_FUNCTION inline
#define SOL_DENOISE_VEC3 glm::dvec3
#define SOL_DENOISE_EXP std::exp
#define SOL_DENOISE_POW std::pow
#define SOL_DENOISE_MAX std::max
#else
#define SOL_DENOISE_FUNCTION
#define SOL_DENOISE_VEC3 vec3
#define SOL_DENOISE_EXP exp
#define SOL_DENOISE_POW pow
#define SOL_DENOISE_MAX max
#endif

/// Passes of the filter: the taps of pass i lie 2^i pixels apart, so the
/// last one reaches 2 · 2^(passes − 1) = 16 pixels from the centre (a
/// fifth pass, to 32, gained nothing measurable on render_bench's scenes).
SOL_CONSTANT(int, kDenoisePasses, 4);
/// The luminance weight's width, in standard deviations of the pixel's
/// noise: neighbours whose light differs by more are another surface's or
/// a shadow's edge.
SOL_CONSTANT(SOL_REAL, kDenoiseSigmaLuminance, 4.0);
/// The normal weight's power of the normals' cosine.
SOL_CONSTANT(SOL_REAL, kDenoiseNormalPower, 128.0);
/// The distance weight's width, in the pixel's distance slope times the
/// tap's offset: a neighbour off the pixel's tangent plane is another surface.
SOL_CONSTANT(SOL_REAL, kDenoiseSigmaDistance, 1.0);
/// Albedos below this (per channel) do not divide the colour.
SOL_CONSTANT(SOL_REAL, kDenoiseMinAlbedo, 0.01);

/// The B3-spline's tap weight at offset -2 ... 2 (1/16, 1/4, 3/8, 1/4, 1/16).
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_tap(int offset) {
  if (offset == 0) return 0.375;
  if (offset == 1 || offset == -1) return 0.25;
  return 0.0625;
}

/// Luminance (Rec. 709), what the colour weight compares.
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_luminance(SOL_DENOISE_VEC3 c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

/// What divides a channel of a pixel's colour, less its emission, before
/// filtering (and multiplies it after): the albedo's channel, or 1 where it
/// is too dark to divide by, or the pixel is a miss (object 0).
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_modulation(SOL_REAL albedo, SOL_REAL object) {
  return object > 0.5 && albedo >= kDenoiseMinAlbedo ? albedo : 1.0;
}

/// A pixel's own noise, the variance of its light's luminance as the mean
/// of `samples` samples: from `moment`, the mean over them of the squared
/// luminance of each one's colour less its emission, `mean`, the luminance
/// of their mean colour less emission, and `modulation`, the luminance of
/// what divides it; the unbiased sample variance over samples − 1, over
/// the modulation squared. Negative (unknown) below 2 samples, where the
/// filter takes the spatial variance instead.
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_own_variance(SOL_REAL moment, SOL_REAL mean, SOL_REAL samples,
                                                       SOL_REAL modulation) {
  if (samples < 1.5) return -1.0;
  return SOL_DENOISE_MAX(moment - mean * mean, 0.0) / ((samples - 1.0) * modulation * modulation);
}

/// From this many samples a pixel on, where its own noise is known well
/// enough (the estimate of a variance from N samples is off by about
/// sqrt(2 / (N − 1)), a third at 16 before the 3 × 3 average), the filtered
/// light stays within kDenoiseClampSigmas of the pixel's own standard
/// deviations of its unfiltered light (in luminance): the filter may not
/// move a pixel further than its noise explains (sol_denoise_clamp).
SOL_CONSTANT(int, kDenoiseClampSamples, 16);
SOL_CONSTANT(SOL_REAL, kDenoiseClampSigmas, 3.0);

/// The filtered light held to within kDenoiseClampSigmas standard
/// deviations (`variance` the pixel's noise, its own averaged over its
/// neighbours: of the light's luminance) of the unfiltered light `before`,
/// in luminance: where the filter moved the luminance further, the move is
/// shortened along its own direction to that bound. (Held channel by
/// channel with the luminance's deviation, a coloured firefly, whose
/// luminance is a fraction of its brightest channel's excess, kept most of
/// it.)
SOL_DENOISE_FUNCTION SOL_DENOISE_VEC3 sol_denoise_clamp(SOL_DENOISE_VEC3 filtered, SOL_DENOISE_VEC3 before,
                                                        SOL_REAL variance) {
  const SOL_REAL spread = kDenoiseClampSigmas * sqrt(SOL_DENOISE_MAX(variance, 0.0));
  const SOL_REAL moved = abs(sol_denoise_luminance(filtered) - sol_denoise_luminance(before));
  return moved <= spread ? filtered : before + (filtered - before) * (spread / moved);
}

/// The edge-stopping weight of neighbour q for pixel p (the B3 tap apart):
/// zero for another object (misses are object 0, of no normal or
/// distance), else the product of the luminance weight (their lights'
/// luminances l against kDenoiseSigmaLuminance standard deviations of p's
/// noise, sqrt(variance_p)), the normal weight (cos^kDenoiseNormalPower)
/// and the distance weight (|z_p − z_q| against kDenoiseSigmaDistance ×
/// slope_p × the offset's length in pixels, slope_p the change of p's
/// distance per pixel). No albedo weight: the light filtered is the
/// albedo's quotient already, and a pixel on a pattern's edge, whose albedo
/// is its samples' blend, takes from both sides.
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_weight(SOL_REAL object_p, SOL_REAL object_q, SOL_REAL l_p, SOL_REAL l_q,
                                                 SOL_REAL variance_p, SOL_DENOISE_VEC3 n_p, SOL_DENOISE_VEC3 n_q,
                                                 SOL_REAL z_p, SOL_REAL z_q, SOL_REAL slope_p, SOL_REAL offset) {
  if (object_p != object_q) return 0.0;
  SOL_REAL w = SOL_DENOISE_EXP(-abs(l_p - l_q) / (kDenoiseSigmaLuminance * sqrt(SOL_DENOISE_MAX(variance_p, 0.0)) + 1e-6));
  if (object_p > 0.5) {
    w *= SOL_DENOISE_POW(SOL_DENOISE_MAX(dot(n_p, n_q), 0.0), kDenoiseNormalPower);
    w *= SOL_DENOISE_EXP(-abs(z_p - z_q) / (kDenoiseSigmaDistance * slope_p * offset + 1e-4 * z_p + 1e-6));
  }
  return w;
}

/// The change of a pixel's distance per pixel: the larger of the central
/// differences along the rows and columns, each from neighbours of the
/// same object (one-sided where only one is; 0 where none is).
SOL_DENOISE_FUNCTION SOL_REAL sol_denoise_slope_along(SOL_REAL z, SOL_REAL z_minus, bool minus_same, SOL_REAL z_plus,
                                                      bool plus_same) {
  if (minus_same && plus_same) return 0.5 * abs(z_plus - z_minus);
  if (minus_same) return abs(z - z_minus);
  if (plus_same) return abs(z_plus - z);
  return 0.0;
}

#ifdef __cplusplus
#undef SOL_DENOISE_VEC3
#undef SOL_DENOISE_EXP
#undef SOL_DENOISE_POW
#undef SOL_DENOISE_MAX
}  // namespace sol::kernel
#endif

#endif  // SOL_DENOISE_H
