// The tone curves, written once: how a linear colour channel, after the
// exposure's scale 2^stops, becomes a displayed value in [0, 1] (before
// the sRGB encoding of 8-bit images and swapchains). Linear outputs (EXR,
// HDR, TIFF, the renderers' float images) take neither: exposure and tone
// belong to the picture made from them, not to the light computed.
//
//   X(Enum, code_name, code, name)
//
//   Enum       the sol::Tone enumerator (sol/display.hpp);
//   code_name  the curve's code, a constant of namespace sol::kernel in C++
//              and a global constant in GLSL ...
//   code       ... and its value, unique;
//   name       the scene key "tone"'s value (and the option's, the panel's
//              and the Python keyword's).
//
// clamp: the value itself, cut at 1 (what a display shows of a linear
// image; everything at or above 1 is the same white). aces: the filmic
// curve of Narkowicz's fit (2015) to the ACES reference rendering and
// sRGB output transforms, (x (2.51 x + 0.03)) / (x (2.43 x + 0.59) + 0.14)
// per channel: a toe below 0.1, middle grey 0.18 shown as 0.27, and a
// shoulder that reaches 1 only at x = 7.24 (a highlight of 4 keeps its
// shading instead of a flat blob). Valid C++ (namespace sol::kernel,
// double) and GLSL (float), as sol/patterns.h.
#ifndef SOL_TONE_H
#define SOL_TONE_H

#include "sol/kernel_constants.h"

// clang-format off
#define SOL_TONE_CURVES(X)             \
  X(Clamp, kToneClamp, 0, "clamp")     \
  X(Aces,  kToneAces,  1, "aces")
// clang-format on

#ifdef __cplusplus
#include <algorithm>
namespace sol::kernel {
#define SOL_TONE_FUNCTION inline
#else
#define SOL_TONE_FUNCTION
#endif

#define SOL_TONE_CODE(Enum, code_name, code, name) SOL_CONSTANT(int, code_name, code);
SOL_TONE_CURVES(SOL_TONE_CODE)
#undef SOL_TONE_CODE

// The curve at x >= 0 before its cut at 1: a value above 1 is clipped by
// the display (the count solrender reports).
SOL_TONE_FUNCTION SOL_REAL sol_tone_curve(int curve, SOL_REAL x) {
  if (curve == kToneAces) return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  return x;
}

// The displayed value in [0, 1] of a linear value already scaled by the
// exposure (negative values, which no renderer makes, show as 0).
SOL_TONE_FUNCTION SOL_REAL sol_tone(int curve, SOL_REAL x) {
#ifdef __cplusplus
  return std::clamp(sol_tone_curve(curve, std::max(x, 0.0)), 0.0, 1.0);
#else
  return clamp(sol_tone_curve(curve, max(x, 0.0)), 0.0, 1.0);
#endif
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_TONE_H
