// Embeds the SPIR-V that sol_add_shader (cmake/SolShaders.cmake) compiles
// from compute/shaders/ into generated headers in the build tree.
#include "sol/vk/shaders.hpp"

#include <cstdint>

namespace sol::vk::shaders {
namespace {
#include "shaders/fill_comp_spv.hpp"
}  // namespace

std::span<const std::uint32_t> fill() { return fill_comp_spv; }

}  // namespace sol::vk::shaders
