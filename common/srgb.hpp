// The sRGB transfer function (IEC 61966-2-1) for 8-bit output: image files,
// 8-bit XR swapchains. The kernels' twin is output_color in
// compute/shaders/march/camera.glsl; both take their constants from
// sol/kernel_constants.h, and the test Kernel.UnormTargetHoldsTheSrgbEncodedColour
// holds the two together.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <sol/display.hpp>
#include <sol/kernel_constants.h>

namespace sol::programs {

/// The sRGB encoding of a linear value clamped to [0, 1], computed in T
/// (float for image files, as the kernels do; double for references).
template <class T>
T srgb_encode(T linear) {
  namespace k = sol::kernel;
  const T c = std::clamp(linear, T(0), T(1));
  return c <= static_cast<T>(k::kSrgbLinearLimit)
             ? static_cast<T>(k::kSrgbLinearSlope) * c
             : static_cast<T>(k::kSrgbScale) * std::pow(c, T(1) / static_cast<T>(k::kSrgbGamma)) - static_cast<T>(k::kSrgbOffset);
}

/// The same as a byte, 0..255 (rounded to nearest).
inline std::uint8_t srgb_byte(float linear) {
  return static_cast<std::uint8_t>(std::lround(srgb_encode(linear) * 255.0f));
}

/// The byte an 8-bit picture holds for a linear colour channel under a
/// display: the exposure's `scale` (Display::scale), the curve `tone` (a
/// sol/tone.h code), the sRGB encoding; as the image writer computes it.
inline std::uint8_t display_byte(float linear, int tone, double scale) {
  return srgb_byte(static_cast<float>(kernel::sol_tone(tone, static_cast<double>(linear) * scale)));
}

}  // namespace sol::programs
