// The Sol ray-marcher on the GPU (or lavapipe): compute/shaders/march.comp
// driven from a sol::World and cameras, producing the same RenderResult
// (image and AOVs) as libsol's CPU reference renderer, sol::CpuRenderer.
//
// The host does in double what must be exact: the camera basis, the world
// made relative to the camera (plane constants), the pattern phase (the
// camera position's fractional part), e^{±z} of the camera; the kernel then
// works near the origin in float, so an observer at (1e6, -1e6, 0.3) sees
// what one at (0, 0, 0.3) sees in a scene invariant under that translation.
#pragma once

#include <array>
#include <cstdint>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec4.hpp>
#include <vulkan/vulkan_core.h>
#include <sol/camera.hpp>
#include <sol/march.hpp>
#include <sol/render.hpp>
#include <sol/renderer.hpp>
#include <sol/scene.hpp>

#include "sol/vk/march_interface.h"
#include "sol/vk/pipeline.hpp"

namespace sol::vk {

class Context;
class StorageImage;

enum class Integrator {
  ClosedForm,  ///< the closed-form geodesic, evaluated at the accumulated arc length (the default)
  RK4,         ///< classical RK4 from step to step with a fixed substep (for comparison)
};

struct MarchOptions {
  Integrator integrator = Integrator::ClosedForm;
  double rk4_step = 0.01;  ///< RK4 substep in arc length, > 0
  /// Use the kernel with every feature compiled in, whatever the world uses
  /// (the default specialises it to the world: planes z = c only, balls,
  /// point lights, fog). Same image; for benchmarks.
  bool all_features = false;
  /// Deferred passes (docs/renderer.md): the hits of worlds with exact
  /// point lights are shaded, the rays of worlds with exact balls that
  /// reach one go on, and in the quotient the rays of small μ (whose
  /// positions take Carlson's integrals) are marched, in later dispatches
  /// over a list of those pixels alone, so that the other pixels do not
  /// pay for that work. Same image; false renders everything in one
  /// dispatch (the comparison the tests make; slower on lavapipe).
  bool deferred = true;
  /// Where the kernel's specialisation constants are applied
  /// (ComputePipelineDesc::specialization_folding): by default folded into
  /// its SPIR-V on a CPU device and handed to the driver on a GPU. Same
  /// image; the tests compare both ways.
  SpecializationFolding specialization_folding = SpecializationFolding::Auto;
  /// Frames a presenter keeps in flight, 1 to kMaxFramesInFlight: each
  /// record() or render() call takes the next of this many descriptor sets,
  /// and may be made while earlier calls' commands still run, provided the
  /// caller has waited for the call made frames_in_flight calls before it
  /// (with 1, for the previous one). A frame's uniforms are written by its
  /// own commands, never by the host, and buffers the renderer replaces
  /// (set_world, larger lists) are kept until no pending frame can read them.
  int frames_in_flight = 1;
};

/// The most frames a MarchRenderer keeps in flight (MarchOptions::frames_in_flight).
inline constexpr int kMaxFramesInFlight = 8;

/// Most images of the objects around the domain in a quotient scene
/// (sol::quotient_images): the kernel's limit (sol/vk/march_interface.h).
/// (A Sol world holds as many objects as on the CPU, sol::kMaxObjects.)
using kernel::kMaxGpuImages;

/// A presenter's 8-bit image that MarchRenderer::record writes the colour
/// into, through `display` (exposure and tone curve, sol/display.hpp) and
/// sRGB-encoded (standard sRGB OETF), as solrender's 8-bit files: for
/// example a swapchain image created with STORAGE usage in a UNORM format,
/// so that the kernel writes the frame straight into it. Not owned.
struct UnormTarget {
  VkImageView view = VK_NULL_HANDLE;      ///< of an image with STORAGE usage, in GENERAL layout when the dispatch runs
  VkFormat format = VK_FORMAT_UNDEFINED;  ///< R8G8B8A8_UNORM or B8G8R8A8_UNORM (the view's format)
  std::uint32_t width = 0, height = 0;    ///< the image's extent
  Display display{};                      ///< the default: the colour clamped to [0, 1]
};

/// One sample of every pixel in an anti-aliased image: where in the pixel
/// (sol::pixel_sample), and its weight in the colour already in the target:
/// 1 overwrites it, 1/(k + 1) makes the k-th sample (k from 0) part of the
/// running mean of k + 1 samples. With `path` >= 0 the sample is a path
/// (sol::Transport::Path, combined sampling): every pixel's path of that
/// index for `seed`, as render()'s k-th sample (a presenter's refinement
/// by paths).
struct PixelSample {
  glm::dvec2 offset{0.5, 0.5};
  double weight = 1.0;
  int path = -1;           ///< the path's index (>= 0), or -1 for direct light
  std::uint64_t seed = 0;  ///< the paths' seed
  /// The sample's index k, as render()'s k-th sample: a camera with an
  /// aperture takes lens point sol::lens_sample(k), glossy reflections in
  /// direct light their random numbers of sample k (a path's: `path`).
  int index = 0;
};

/// The ray-marcher on a Vulkan device, a sol::Renderer (sol/renderer.hpp).
/// It holds one world at a time, prepared once by set_world (checks,
/// features, the quotient's images and the exact objects' tables uploaded;
/// the kernel for those features is built by the first frame that needs it
/// and kept); every frame then only sends its cameras:
///
///   sol::vk::MarchRenderer renderer(context);
///   renderer.set_world(scene);                       // once per world
///   renderer.record(command_buffer, cameras, w, h, target);  // per frame (presenters)
///   sol::RenderResult image = renderer.render(cameras, options);  // or with AOVs, read back
class MarchRenderer final : public Renderer {
 public:
  /// Checks the options (InvalidArgument); builds no pipeline: each variant
  /// of the kernel is built when a frame first needs it (VulkanError there).
  explicit MarchRenderer(Context& context, const MarchOptions& options = {});
  ~MarchRenderer() override;
  MarchRenderer(MarchRenderer&&) noexcept;
  MarchRenderer& operator=(MarchRenderer&&) noexcept;

  /// Prepares `world` for every later frame. Throws sol::InvalidArgument for
  /// an invalid world (one the CPU renderer refuses too); sol::NotImplemented
  /// for a world the kernel does not render (supports(): exact balls in a
  /// world of more than sol::kListedObjects objects, in the quotient more
  /// than kMaxGpuImages images,
  /// ...), which the CPU renderer does. Frames recorded before
  /// may still run: they keep reading the previous world's buffers, which
  /// live until they are done (MarchOptions::frames_in_flight).
  void set_world(const World& world) override;
  /// The prepared world (std::logic_error before set_world).
  const MarchWorld& world() const override;
  /// How many deferred passes (MarchOptions::deferred) the world's frames
  /// take after the march pass: the shade pass (exact point lights) and the
  /// resume pass (exact balls, in Sol with the closed form; every quotient
  /// world, for its rays of small μ); 0 for worlds
  /// rendered in one dispatch. (Frames whose lists outgrow one indirect
  /// dispatch or the device's largest storage buffer binding, 48 bytes a
  /// pixel, render in one dispatch too.) std::logic_error before set_world.
  int deferred_passes() const;

  /// Renders the world from one or two eyes (side by side, left eye first)
  /// with the AOVs, read back: sol::Renderer::render. RenderResult::device_ms
  /// is the dispatches' time on the device. With RenderOptions::samples > 1
  /// one dispatch per sample; with a finite max_dispatch_ms in tiles (each
  /// computed as in one dispatch: they change no pixel). Throws
  /// sol::InvalidArgument for invalid options or cameras, more than two
  /// eyes, or no world.
  RenderResult render(std::span<const Camera> eyes, const RenderOptions& options) override;
  using Renderer::render;
  /// "vulkan 'DEVICE NAME'".
  std::string description() const override;
  /// The denoiser (sol/denoise.hpp) on the device, in float: its filter
  /// pipeline built at the first call. Same checks as sol::denoise.
  void denoise(RenderResult& image, int eyes = 1) override;

  /// For presenters: records the kernel for one or two eyes (side by side,
  /// each width × height, left eye on the left) into the caller's command
  /// buffer, writing the linear RGBA colour alone (no AOVs) into `target`, an
  /// R32G32B32A32_SFLOAT StorageImage of at least (eyes · width) × height,
  /// in GENERAL layout. Submits nothing, and records no barrier for
  /// `target`: the caller orders the dispatch against earlier and later uses
  /// of it. The frame's uniforms are written by the recorded commands, which
  /// first wait for the kernels of frames submitted before them to finish;
  /// frames may be recorded while earlier ones run, up to
  /// MarchOptions::frames_in_flight (each call counts one). Keep `target`
  /// alive until this frame finishes.
  /// Same checks and exceptions as render(). `sample` takes one sample of
  /// every pixel into the running mean already in `target` (progressive
  /// anti-aliasing: the caller orders the dispatch after the previous one).
  void record(VkCommandBuffer command_buffer, std::span<const Camera> eyes, int width, int height,
              const StorageImage& target, const PixelSample& sample = {});

  /// The same into a caller's 8-bit image, sRGB-encoded: `target` must be of
  /// at least (eyes · width) × height and its format one that
  /// can_write_unorm() accepts (else sol::InvalidArgument). Colour as
  /// render()'s, encoded, within 1 in 255.
  void record(VkCommandBuffer command_buffer, std::span<const Camera> eyes, int width, int height,
              const UnormTarget& target);

  /// Makes room now for frames of up to eyes × width × height pixels (the
  /// deferred passes' lists), so that no later frame of that size allocates
  /// device memory; a presenter calls it when its largest frame changes.
  void reserve(int width, int height, int eyes);

  /// The same with the AOVs, for a presenter's probes (solview's panel
  /// shows the mean march steps without waiting for a read-back): the
  /// colour into `color`, the object, the distance and the steps into `hit`
  /// and the hit point into `point`, laid out as render() reads them back;
  /// each an R32G32B32A32_SFLOAT StorageImage of at least (eyes · width) ×
  /// height in GENERAL layout (else sol::InvalidArgument).
  void record(VkCommandBuffer command_buffer, std::span<const Camera> eyes, int width, int height,
              const StorageImage& color, const StorageImage& hit, const StorageImage& point);

  /// Whether record() can write a UnormTarget of `format` on the context's
  /// device: R8G8B8A8_UNORM or B8G8R8A8_UNORM, usable as a storage image
  /// (optimal tiling), and the shaderStorageImageWriteWithoutFormat feature
  /// (Context::storage_write_without_format).
  static bool can_write_unorm(const Context& context, VkFormat format);

  /// Exact balls of a larger radius render on the CPU only: the kernel
  /// starts its Newton solves from sol::ConnectionTable's seeds and keeps
  /// to the connection it tracks, and beyond this radius a few pixels of a
  /// far observer's view landed on a longer connection, off the sphere by up
  /// to 4e-2 (test Kernel.ExactBallsLieOnTheGeodesicSphere; at 2
  /// and below every hit lies within 1e-4 of the geodesic sphere).
  static constexpr double kMaxExactBallRadius = 2.0;

  /// Monodromies of a larger |trace| render on the CPU only: γ3 scales x
  /// by λ ≈ |trace| (and y by 1/λ), and past this the kernel's float no
  /// longer places a teleported ray in D as the CPU's double does (a ball in
  /// the bundle of [[t - 1, 1], [t - 2, 1]], 48 × 32, pixels more than 0.05
  /// off the CPU's: none up to t = 200, 0.1 % at 300, 0.7 % at 1000, 3.7 %
  /// at 10^4, 36 % at 10^9 + 1; test Kernel.LargeMonodromyTracesRenderOnTheCpu).
  static constexpr long long kMaxMonodromyTrace = 200;

  /// Whether the kernel renders the world: all but monodromies of |trace|
  /// above kMaxMonodromyTrace, those with exact point
  /// lights of a reach above sol::ConnectionTable::kReach (its seeds stop
  /// there), or in the quotient above 1 (the light's images within reach
  /// of the domain, sol::quotient_light_images, outgrow kMaxGpuLightImages),
  /// those with exact balls above kMaxExactBallRadius, and quotients with
  /// more than kMaxGpuImages images near the domain (a crowded world, or a
  /// monodromy's small fibre). set_world throws sol::NotImplemented for
  /// those; the CPU renderer takes each of them. A world neither renders
  /// (invalid, or more images than the CPU's field takes) is supported
  /// here: set_world says why it is refused.
  static bool supports(const World& world, Transport transport = Transport::Direct);
  /// Why the kernel does not render the world by `transport`, naming the
  /// field and saying that the CPU renderer does ("" when it does:
  /// supports()). A glowing ball's glow_reach above the seed table's reach
  /// keeps path tracing on the CPU alone (a path frame, render() by paths
  /// or a presenter's path sample, is refused with this reason); direct
  /// light never reads it.
  static std::string unsupported(const World& world, Transport transport = Transport::Direct);

 private:
  struct Frame;
  Frame prepare_frame(std::span<const Camera> eyes, int width, int height, bool aovs, bool srgb_unorm,
                      const PixelSample& sample = {}, bool sample_aovs = true, bool path = false);
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// The connection solver's seeds the kernel reads (sol::ConnectionTable:
/// the minimisers', or with `longer` the longer connections'), built by
/// libsol's solver when sol::vk was built and compiled in.
std::span<const float> connection_seeds(bool longer);

}  // namespace sol::vk
