#include "sol/display.hpp"

#include <cmath>

#include "field_error.hpp"

namespace sol {

const char* tone_name(Tone tone) {
  switch (tone) {
#define SOL_TONE_NAME(Enum, code_name, code, name) \
  case Tone::Enum:                                 \
    return name;
    SOL_TONE_CURVES(SOL_TONE_NAME)
#undef SOL_TONE_NAME
  }
  return "clamp";
}

std::optional<Tone> tone_from_name(std::string_view text) {
#define SOL_TONE_FROM_NAME(Enum, code_name, code, name) \
  if (text == name) return Tone::Enum;
  SOL_TONE_CURVES(SOL_TONE_FROM_NAME)
#undef SOL_TONE_FROM_NAME
  return std::nullopt;
}

std::string tone_names() {
  std::string names;
#define SOL_TONE_LISTED(Enum, code_name, code, name) names += std::string(names.empty() ? "" : ", ") + name;
  SOL_TONE_CURVES(SOL_TONE_LISTED)
#undef SOL_TONE_LISTED
  return names;
}

namespace detail {
void check_display(const Display& display) {
  if (!(std::abs(display.exposure) <= Display::kMaxExposure)) {
    field_error("exposure", "exposure must be finite and within ±20 stops");
  }
  if (!tone_from_name(tone_name(display.tone))) field_error("tone", "tone must be one of " + tone_names());
}
}  // namespace detail

void validate(const Display& display) {
  detail::validate_as("sol::validate(Display)", [&] { detail::check_display(display); });
}

}  // namespace sol
