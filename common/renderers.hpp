// Choosing a renderer, as the programs do (solrender's --device): the
// Vulkan kernel (sol::vk::MarchRenderer on a GPU, else lavapipe) or the
// CPU reference (sol::CpuRenderer), behind sol::Renderer. A Vulkan
// renderer keeps its own device context; kernels compiled once are kept in
// the pipeline cache between runs.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <sol/renderer.hpp>
#ifdef SOL_HAVE_VULKAN
#include <sol/vk/march.hpp>
#endif

namespace sol::programs {

enum class Device {
  Auto,    ///< the Vulkan kernel where there is a device and it draws the world, else the CPU
  Vulkan,  ///< the Vulkan kernel, or an error
  Cpu,     ///< the CPU reference renderer
};

/// What a program asks of its renderer.
struct RendererChoice {
  Device device = Device::Auto;
  bool rk4 = false;        ///< the kernel's RK4 integrator (Vulkan only) instead of the closed form
  double rk4_step = 0.01;  ///< its substep in arc length, > 0
  bool validation = false; ///< the Vulkan validation layers
  /// How the renders will be made: a world the kernel path-traces on the
  /// CPU only (MarchRenderer::unsupported) takes the CPU then.
  Transport transport = Transport::Direct;
};

/// Whether this build has the Vulkan kernel.
bool has_vulkan();

#ifdef SOL_HAVE_VULKAN
/// The kernel's options for a choice: its integrator and RK4 step (what
/// make_renderer gives the kernel, and presenters that record it themselves).
vk::MarchOptions march_options(const RendererChoice& choice);
#endif

/// A renderer for `world` (set_world done): with Device::Auto the Vulkan
/// kernel when this build has it, a device opens and the kernel draws the
/// world, else the CPU, saying why through `note` (one line, no program
/// name); with Device::Vulkan the kernel or an exception saying why;
/// Device::Cpu the CPU renderer. Asking RK4 of the CPU is an
/// InvalidArgument.
std::unique_ptr<sol::Renderer> make_renderer(const RendererChoice& choice, const sol::World& world,
                                             const std::function<void(const std::string&)>& note);

}  // namespace sol::programs
