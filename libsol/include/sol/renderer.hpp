// The one interface of Sol's renderers: the CPU reference
// (sol::CpuRenderer, sol/render.hpp) and the Vulkan kernel
// (sol::vk::MarchRenderer, compute/include/sol/vk/march.hpp) draw the same
// pictures through it, and the programs (solrender, solview, solxr),
// render_bench and the Python module choose one and use it alike:
//
//   std::unique_ptr<sol::Renderer> renderer = ...;       // CPU or Vulkan
//   renderer->set_world(scene);                           // once per world
//   sol::RenderResult image = renderer->render(scene.camera, {.width = 256, .height = 256});
//   sol::RenderResult pair = renderer->render_stereo(scene.camera, 0.064, options);
//
// A world is prepared once (validation, features, the quotient's images,
// and for the kernel its tables and pipelines); every render then takes
// one or more eyes (cameras), each width × height, side by side in one
// image, left eye first, and one options struct.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "sol/camera.hpp"
#include "sol/march.hpp"
#include "sol/scene.hpp"

namespace sol {

/// How a renderer makes an image beyond its world and eyes.
/// How light reaches the eye: Direct (each hit lit by the lights, with
/// ambient light, mirrors and emission: sol::CpuRenderer, the kernel), or
/// Path: path tracing (diffuse interreflection, emission, mirrors and the
/// lights by next-event estimation; no ambient light), on the CPU renderer
/// (docs/lighting.md, "Path tracing").
enum class Transport { Direct, Path };

/// How the path tracer reaches glowing balls and boxes from a diffuse
/// hit: both strategies combined by multiple importance sampling
/// (the default), or one alone (the same expected image, for comparing the
/// estimators): sampling the surface's reflection (a path that meets a
/// glowing object counts its emission), or next-event estimation (a point
/// of a glowing object's surface sampled and connected; what it cannot
/// draw, such as a geodesic longer than a ball's glow_reach or a quotient's
/// image it does not list, reflection sampling still counts;
/// docs/lighting.md, "Path tracing").
enum class PathSampling { Combined, ReflectionOnly, GlowOnly };

struct RenderOptions {
  int width = 512;   ///< of each eye, in [1, 16384]
  int height = 512;  ///< in [1, 16384]
  /// Samples per pixel, in [1, 4096]: the colour is their mean
  /// (anti-aliasing, at sol::pixel_sample 0, 1, ...; a box filter over the
  /// pixel); the AOVs are the pixel centre's (sample 0), but for the
  /// guides' albedo and emission, which are the samples' mean.
  int samples = 1;
  /// The index of the first of them: the samples are first_sample ..
  /// first_sample + samples - 1 (their points sol::pixel_sample, their
  /// paths' indices), so that renders of consecutive ranges, weighted by
  /// their counts, make the render of all of them (solrender --time-limit
  /// renders in such batches). In [0, kMaxFirstSample]; above 0 the AOVs,
  /// which are sample 0's, are not rendered: `aovs` must be false.
  int first_sample = 0;
  static constexpr int kMaxFirstSample = 1 << 24;
  /// The CPU renderer's threads (0: all hardware threads).
  unsigned threads = 0;
  /// Transport::Path: each sample one path from the camera (its random
  /// numbers from `seed`, the pixel and the sample: the same image on any
  /// number of threads); the colour their mean.
  Transport transport = Transport::Direct;
  std::uint64_t seed = 0;
  PathSampling path_sampling = PathSampling::Combined;
  /// Device renderers: each dispatch (one sample of a tile) is sized from
  /// the earlier ones' times to take about half of this on the device, so
  /// that long renders never hold it in one dispatch (a display's
  /// watchdog), report progress and can stop. Infinite (the default): the
  /// whole image in one dispatch per sample. Tiles change no pixel.
  double max_dispatch_ms = std::numeric_limits<double>::infinity();
  /// The arbitrary output variables too (RenderResult's object ... steps).
  /// False: the colour alone, the AOV vectors left empty, so a renderer
  /// neither reads them back from a device nor holds them (solrender
  /// without --aov).
  bool aovs = true;
  /// The denoiser's guides: RenderResult::albedo and ::emission (the means
  /// over the range's samples) and, with `aovs`, ::normal (sample 0's).
  /// Without `aovs` (a batch after the first) the albedo and emission
  /// alone, which batches join as they join their colours. Asked for apart: the kernel's three more
  /// images, two of them joined by every sample, cost up to a twentieth of
  /// a path render's device time on lavapipe (256 × 192, 16 paths:
  /// lattice-balls 1647 -> 1724 ms, plane 367 -> 386 ms).
  bool guides = false;
  /// Called now and then with the finished fraction in [0, 1] (0 first, 1 last).
  std::function<void(double)> progress;
  /// When set and true, the render stops early and throws sol::Cancelled.
  const std::atomic<bool>* cancel = nullptr;
  /// Where the colour goes instead of RenderResult::rgba, band by band
  /// from the top: (first row, rows, their 4 × W × rows values, W the width
  /// of all eyes side by side). RenderResult::rgba is then left empty. A
  /// device renderer hands each band over as it reads it back, so the
  /// colour is never held whole on the host (solrender streams it into the
  /// image file's encoder); the CPU renderer hands over its whole image.
  std::function<void(int first_row, int rows, std::span<const float> rgba)> rows;
};

/// An image and its arbitrary output variables, row-major, row 0 at the top.
struct RenderResult {
  int width = 0, height = 0;
  std::vector<float> rgba;      ///< 4 per pixel, linear RGB, alpha 1; the rest empty without RenderOptions::aovs
  std::vector<float> object;    ///< per pixel: 0 = no hit, k = k-th object (1-based)
  std::vector<float> distance;  ///< arc length to the hit (0 on a miss)
  std::vector<float> px, py, pz;  ///< hit point, world Sol coordinates (0 on a miss)
  std::vector<float> steps;     ///< march steps used
  /// 3 per pixel: the mean over the pixel's samples (as the colour) of
  /// their camera rays' first hits' albedo (its colour times its pattern
  /// and texture, whatever its material; 0 on a miss): the denoiser's guide
  /// (sol/denoise.hpp); with RenderOptions::guides, else empty.
  std::vector<float> albedo;
  /// 3 per pixel: the mean over the pixel's samples of what their first
  /// hits emit towards the eye (the object's emission times the fog's
  /// transmittance over the camera ray; 0 on a miss): the part of the
  /// colour that needs no light, which the denoiser takes out before it
  /// divides by the albedo; with RenderOptions::guides, else empty.
  std::vector<float> emission;
  /// Per pixel: the mean over the pixel's samples of the squared luminance
  /// (Rec. 709) of each one's colour less its emission, from which the
  /// denoiser takes the pixel's own noise (with `samples`); with
  /// RenderOptions::guides, else empty (the denoiser then estimates the
  /// noise from the neighbours). Not written to image files.
  std::vector<float> light_moment;
  /// How many samples a pixel's colour is the mean of (RenderOptions::samples,
  /// or every batch's together); 0 where unknown.
  int samples = 0;
  /// 3 per pixel: the hit's unit surface normal in the frame components at
  /// the hit, facing the ray (a solid seen from inside: its inward normal);
  /// 0 on a miss; with RenderOptions::guides, else empty.
  std::vector<float> normal;
  /// Per pixel: how many of its marches (over all its samples: the camera
  /// rays, mirrors' reflected rays, paths' segments, shadow rays) stopped at
  /// the world's max_steps before they met an object or reached
  /// max_distance. Such a ray is drawn as a miss (a shadow ray as
  /// unblocked): a pixel with a count here may be darker (or lighter) than
  /// the scene is; a larger max_steps draws it.
  std::vector<float> out_of_steps;
  /// The same over the whole image, counted with or without the AOVs.
  std::uint64_t rays_out_of_steps = 0;
  double device_ms = 0.0;       ///< a device renderer's time on the device (its dispatches'); 0 on the CPU
};

class Renderer {
 public:
  virtual ~Renderer() = default;

  /// Prepares `world` once for every later render: validates it
  /// (InvalidArgument naming the field) and prepares what the renderer
  /// needs of it; NotImplemented for a world this renderer does not draw.
  virtual void set_world(const World& world) = 0;
  /// The prepared world (std::logic_error before set_world).
  virtual const MarchWorld& world() const = 0;

  /// Renders the world from `eyes` (one or more cameras), each
  /// options.width × options.height, side by side in one image (left eye
  /// first). Throws InvalidArgument for invalid cameras or options.
  virtual RenderResult render(std::span<const Camera> eyes, const RenderOptions& options) = 0;

  /// Where it renders, for people: "cpu (2 threads)", "vulkan 'llvmpipe ...'".
  virtual std::string description() const = 0;

  /// Replaces the colour of `image` (a render of this renderer's with its
  /// AOVs, `eyes` side by side) by the denoiser's (sol/denoise.hpp) where
  /// the renderer computes: on the host in double (the default, the CPU
  /// renderer's), on the device in float (the kernel's). InvalidArgument
  /// for an image without AOVs.
  virtual void denoise(RenderResult& image, int eyes = 1);

  /// One eye.
  RenderResult render(const Camera& camera, const RenderOptions& options);
  /// Both eyes of sol::stereo_eyes(camera, ipd) side by side.
  RenderResult render_stereo(const Camera& camera, double ipd, const RenderOptions& options);
};

/// The checks every renderer makes of a render's eyes and options (sizes,
/// samples, the equirectangular aspect, each camera): InvalidArgument
/// naming `who` and the field. With `bytes_per_pixel` (the renderer's peak
/// memory per pixel of all eyes), a render that needs more memory than the
/// system has available (MemAvailable, where /proc/meminfo says) is
/// refused up front with both figures, rather than failing late.
void validate_render(std::span<const Camera> eyes, const RenderOptions& options, const char* who,
                     double bytes_per_pixel = 0.0);

/// Memory the system can give a process now without swapping (Linux:
/// MemAvailable), in bytes; 0 where it cannot be told.
double available_memory_bytes();

/// This process's memory: resident now and at its peak (Linux: VmRSS and
/// VmHWM of /proc/self/status), in bytes; 0 where it cannot be told. The
/// programs report the peak (a long render's memory must stay flat).
struct ProcessMemory {
  double resident_bytes = 0.0;
  double peak_bytes = 0.0;
};
ProcessMemory process_memory();

/// One-shot: renderer.set_world(scene), then the scene's camera.
RenderResult render_scene(Renderer& renderer, const Scene& scene, const RenderOptions& options);

}  // namespace sol
