// The compute shaders built into Sol::vk, as SPIR-V words (compiled from
// compute/shaders/ at build time by sol_add_shader, cmake/SolShaders.cmake).
#pragma once

#include <cstdint>
#include <span>

namespace sol::vk::shaders {

/// fill.comp (8×8 groups): binding 0 an rgba32f storage image, push constant
/// one float `value`; writes (x, y, value, 1) to every pixel (x, y). A test
/// of the host library.
std::span<const std::uint32_t> fill();

}  // namespace sol::vk::shaders
