// How a rendered (linear) image is shown: the exposure in stops and the
// tone curve (sol/tone.h), applied to 8-bit images and displays only.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "sol/tone.h"

namespace sol {

/// The tone curves of SOL_TONE_CURVES (sol/tone.h).
enum class Tone {
#define SOL_TONE_ENUMERATOR(Enum, code_name, code, name) Enum = code,
  SOL_TONE_CURVES(SOL_TONE_ENUMERATOR)
#undef SOL_TONE_ENUMERATOR
};

/// The scene key's name of a curve ("clamp", "aces").
const char* tone_name(Tone tone);
/// The curve of a name, or none.
std::optional<Tone> tone_from_name(std::string_view name);
/// Every curve's name, comma-separated ("clamp, aces"): for messages and help.
std::string tone_names();

/// The scene keys "exposure" and "tone" (docs/scene-format.md).
struct Display {
  /// Stops: the linear colour is scaled by 2^exposure before the curve; in
  /// [-kMaxExposure, kMaxExposure].
  double exposure = 0.0;
  Tone tone = Tone::Clamp;
  static constexpr double kMaxExposure = 20.0;

  bool operator==(const Display&) const = default;
  /// 2^exposure.
  double scale() const { return std::exp2(exposure); }
  /// Whether the display cuts the value: the curve exceeds 1 there.
  bool clips(double linear) const { return kernel::sol_tone_curve(static_cast<int>(tone), linear * scale()) > 1.0; }
};

/// Checks the display (a finite exposure within ±kMaxExposure); throws
/// InvalidArgument naming the field ("exposure ...").
void validate(const Display& display);

}  // namespace sol
