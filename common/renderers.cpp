#include "renderers.hpp"

#include <optional>
#include <stdexcept>

#include <sol/error.hpp>
#include <sol/render.hpp>
#ifdef SOL_HAVE_VULKAN
#include <sol/vk/context.hpp>
#include <sol/vk/march.hpp>
#endif

namespace sol::programs {

#ifdef SOL_HAVE_VULKAN
namespace {

// The kernel with the device context it runs on (the context outlives it).
class VulkanRenderer final : public sol::Renderer {
 public:
  VulkanRenderer(const vk::ContextOptions& options, const vk::MarchOptions& march)
      : m_context(options), m_renderer(m_context, march) {}
  void set_world(const World& world) override { m_renderer.set_world(world); }
  const MarchWorld& world() const override { return m_renderer.world(); }
  RenderResult render(std::span<const Camera> eyes, const RenderOptions& options) override {
    return m_renderer.render(eyes, options);
  }
  using Renderer::render;
  std::string description() const override { return m_renderer.description(); }

 private:
  vk::Context m_context;
  vk::MarchRenderer m_renderer;
};

}  // namespace

bool has_vulkan() { return true; }

vk::MarchOptions march_options(const RendererChoice& choice) {
  vk::MarchOptions march;
  march.integrator = choice.rk4 ? vk::Integrator::RK4 : vk::Integrator::ClosedForm;
  march.rk4_step = choice.rk4_step;
  return march;
}
#else
bool has_vulkan() { return false; }
#endif

std::unique_ptr<sol::Renderer> make_renderer(const RendererChoice& choice, const sol::World& world,
                                             const std::function<void(const std::string&)>& note) {
  if (choice.rk4 && choice.device == Device::Cpu) throw InvalidArgument("the RK4 integrator needs the Vulkan kernel");
#ifdef SOL_HAVE_VULKAN
  if (choice.device != Device::Cpu) {
    std::string why = vk::MarchRenderer::unsupported(world, choice.transport);
    if (!why.empty() && choice.device == Device::Vulkan) throw NotImplemented(why + " (--device cpu or auto)");
    if (!why.empty() && !choice.rk4) {
      note(why + "; rendering on the CPU");
    } else {
      if (!why.empty()) throw NotImplemented(why);  // RK4 runs on the kernel only
      vk::ContextOptions options;
      options.pipeline_cache_dir = vk::default_pipeline_cache_dir();  // compiled kernels kept between runs
      options.validation = choice.validation;
      std::unique_ptr<sol::Renderer> renderer;
      try {
        renderer = std::make_unique<VulkanRenderer>(options, march_options(choice));
      } catch (const std::exception& e) {
        if (choice.device == Device::Vulkan || choice.rk4) throw;
        note(std::string("no Vulkan device (") + e.what() + "); rendering on the CPU");
      }
      if (renderer) {
        try {
          renderer->set_world(world);
          return renderer;
        } catch (const NotImplemented& e) {  // a world the kernel does not draw after all: the CPU does
          if (choice.device == Device::Vulkan || choice.rk4) throw;
          note(std::string(e.what()) + "; rendering on the CPU");
        }
      }
    }
  }
#else
  (void)note;  // nothing to say: the CPU is all there is
  if (choice.device == Device::Vulkan || choice.rk4) {
    throw NotImplemented("this build has no Vulkan kernel (SOL_BUILD_VULKAN=OFF): use the CPU renderer");
  }
#endif
  return std::make_unique<sol::CpuRenderer>(world);
}

}  // namespace sol::programs
