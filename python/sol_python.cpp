// The Python module `sol`: libsol from Python (pybind11). Points and
// directions are sequences of three floats (or NumPy arrays) in, NumPy
// float64 arrays out; the vectorised entry points take arrays of shape
// (N, 3) and return (N, 3) or (N,) arrays, looping in C++. libsol's
// exceptions arrive as Python exceptions with the C++ message, all
// sol.SolError: InvalidArgument as sol.InvalidArgumentError and OutOfRange
// as sol.OutOfRangeError (both ValueError too), NotImplemented as
// sol.UnsupportedError (NotImplementedError too). The package around this
// module is python/sol/; docs/python.md has the reference and examples.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <sol/sol.hpp>

#ifdef SOL_PYTHON_IMAGES
#include "image_file.hpp"  // Sol::programs: solrender's image writer and sRGB bytes
#include "renderers.hpp"   // and its choice of renderer (make_renderer)
#include "sampling.hpp"    // and its batches (--time-limit, --noise-target)
#include "srgb.hpp"
#endif

namespace py = pybind11;

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

glm::dvec3 vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

py::array_t<double> array(const glm::dvec3& v) {
  py::array_t<double> out(3);
  auto o = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < 3; ++i) o(i) = v[static_cast<glm::length_t>(i)];
  return out;
}

// Ctrl-C in long work done with the GIL released: the calling thread (the
// one Python's signal handlers run on) takes the GIL every 100 ms to run
// them; what they raise (KeyboardInterrupt) stops the work and reaches the
// caller as it is.
class Interrupts {
 public:
  void check() {
    const auto now = std::chrono::steady_clock::now();
    if (now - m_last < std::chrono::milliseconds(100)) return;
    m_last = now;
    const py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

 private:
  std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
};

// An (N, 3) array's rows (a single point is one row).
std::vector<glm::dvec3> rows(const Points& points, const char* name) {
  const py::buffer_info b = points.request();
  if (!((b.ndim == 1 && b.shape[0] == 3) || (b.ndim == 2 && b.shape[1] == 3))) {
    throw sol::InvalidArgument(std::string("sol: ") + name + " must have shape (3,) or (N, 3)");
  }
  const auto n = b.ndim == 1 ? 1 : static_cast<std::size_t>(b.shape[0]);
  const auto* d = static_cast<const double*>(b.ptr);
  std::vector<glm::dvec3> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
  return out;
}

py::array_t<double> rows_array(const std::vector<glm::dvec3>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (py::ssize_t c = 0; c < 3; ++c) o(static_cast<py::ssize_t>(i), c) = v[i][static_cast<glm::length_t>(c)];
  }
  return out;
}

py::list connections(const std::vector<sol::Connection>& cs) {
  py::list out;
  for (const sol::Connection& c : cs) out.append(py::make_tuple(array(c.direction), c.length));
  return out;
}

// A per-pixel channel of a render as an (H, W) or (H, W, C) float32 array.
py::array_t<float> image(const std::vector<float>& values, int height, int width, int channels) {
  std::vector<py::ssize_t> shape{height, width};
  if (channels > 1) shape.push_back(channels);
  py::array_t<float> out(shape);
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// A render's images as the Python module hands them out: a dict of float32
// arrays (rgba, object, distance, point, steps).
py::dict render_dict(const sol::RenderResult& r) {
  py::dict out;
  out["rgba"] = image(r.rgba, r.height, r.width, 4);
  if (r.object.empty()) return out;  // the colour alone (aovs=False)
  std::vector<float> point(3 * r.px.size());
  for (std::size_t i = 0; i < r.px.size(); ++i) {
    point[3 * i] = r.px[i];
    point[3 * i + 1] = r.py[i];
    point[3 * i + 2] = r.pz[i];
  }
  out["object"] = image(r.object, r.height, r.width, 1);
  out["distance"] = image(r.distance, r.height, r.width, 1);
  out["point"] = image(point, r.height, r.width, 3);
  out["steps"] = image(r.steps, r.height, r.width, 1);
  if (!r.albedo.empty()) out["albedo"] = image(r.albedo, r.height, r.width, 3);
  if (!r.emission.empty()) out["emission"] = image(r.emission, r.height, r.width, 3);
  if (!r.normal.empty()) out["normal"] = image(r.normal, r.height, r.width, 3);
  if (!r.out_of_steps.empty()) out["out_of_steps"] = image(r.out_of_steps, r.height, r.width, 1);
  return out;
}

// solrender's --transport by name, for `who`'s keyword.
sol::Transport transport_named(const std::string& name, const char* who) {
  if (name == "direct") return sol::Transport::Direct;
  if (name == "path") return sol::Transport::Path;
  throw sol::InvalidArgument(std::string(who) + ": transport must be \"direct\" or \"path\", not \"" + name + "\"");
}

// sol.CpuRenderer: the renderer with its world prepared once, the scene's
// camera and samples its defaults.
struct PyCpuRenderer {
  sol::CpuRenderer renderer;
  sol::Camera camera;
  int samples = 1;
  // Safe while another Python thread renders with it (sol::CpuRenderer:
  // that render finishes with the world it started with); the world is
  // prepared without the GIL (a quotient's field takes a while).
  void set_scene(const sol::Scene& scene) {
    {
      py::gil_scoped_release release;
      renderer.set_world(scene);
    }
    camera = scene.camera;
    samples = scene.samples;
  }
  // A render from `eye` (the scene's camera when none), `samples` 0 the
  // scene's, by `transport` ("direct" or "path", solrender's --transport)
  // with the path tracer's `seed` (solrender's --seed).
  sol::RenderResult render(int width, int height, int samples_given, unsigned threads, const std::optional<sol::Camera>& eye,
                           const std::string& transport = "direct", long long seed = 0) {
    const sol::Camera from = eye.value_or(camera);
    if (seed < 0) throw sol::InvalidArgument("sol.CpuRenderer.render: seed must be 0 or more, not " + std::to_string(seed));
    const sol::RenderOptions options{.width = width,
                                     .height = height,
                                     .samples = samples_given == 0 ? samples : samples_given,
                                     .threads = threads,
                                     .transport = transport_named(transport, "sol.CpuRenderer.render"),
                                     .seed = static_cast<std::uint64_t>(seed),
                                     .guides = true};  // (the dict's albedo, emission and normal)
    // The CPU renderer's 88 bytes a pixel and the arrays it becomes here,
    // 64 more (the result lives until they are made): refused up front
    // where that cannot fit.
    sol::validate_render(std::span(&from, 1), options, "sol.CpuRenderer.render", 152.0);
    Interrupts interrupts;
    sol::RenderOptions interruptible = options;
    interruptible.progress = [&interrupts](double) { interrupts.check(); };
    py::gil_scoped_release release;  // the rows render on threads of their own
    return renderer.render(from, interruptible);
  }
};

#ifndef SOL_VULKAN_MISSING
#define SOL_VULKAN_MISSING ""
#endif
// What the build lacked for the Vulkan kernel ("" where it has it, or was not asked for it).
constexpr const char* sol_vulkan_missing() { return SOL_VULKAN_MISSING; }

#ifdef SOL_PYTHON_IMAGES
// sol._Renderer (sol.Renderer wraps it): either device behind
// sol::Renderer, chosen as solrender's --device chooses (make_renderer).
// Renders with the GIL released; the progress callback and Python's
// signal handlers run on the calling thread at most every 100 ms (a
// device's dispatches are tiled to about 50 ms, as solrender's), and what
// they raise cancels the render (sol::RenderOptions::cancel) and reaches
// the caller.
struct PyRenderer {
  sol::programs::RendererChoice choice;
  std::unique_ptr<sol::Renderer> renderer;
  sol::Camera camera;
  int samples = 1;
  std::vector<std::string> notes;  // why auto took the CPU, if it did
  std::string description;         // the renderer's, for people
  bool on_cpu = false;
  // Held by a render and by set_scene (both without the GIL): another
  // Python thread's set_scene waits for the render under way to finish.
  std::mutex busy;

  static sol::programs::Device device_named(const std::string& name) {
    if (name == "auto") return sol::programs::Device::Auto;
    if (name == "vulkan") return sol::programs::Device::Vulkan;
    if (name == "cpu") return sol::programs::Device::Cpu;
    throw sol::InvalidArgument("sol.Renderer: device must be \"auto\", \"vulkan\" or \"cpu\", not \"" + name + "\"");
  }

  void set_scene(const sol::Scene& scene) {
    if (choice.device == sol::programs::Device::Vulkan && !sol::programs::has_vulkan()) {
      throw sol::NotImplemented(std::string("sol.Renderer: device=\"vulkan\": this sol was built without the Vulkan kernel") +
                                (sol_vulkan_missing()[0] ? std::string(" (missing when it was built: ") + sol_vulkan_missing() + ")"
                                                         : std::string()) +
                                "; device=\"cpu\" or \"auto\" render on the CPU (docs/python.md)");
    }
    std::vector<std::string> said;
    try {
      py::gil_scoped_release release;  // a kernel's first build and a quotient's field take a while
      const std::lock_guard lock(busy);
      renderer = sol::programs::make_renderer(choice, scene, [&said](const std::string& note) { said.push_back(note); });
    } catch (const sol::NotImplemented& e) {
      std::string what = e.what();
      const std::string cli = "(--device cpu or auto)";
      if (const auto at = what.find(cli); at != std::string::npos) what.replace(at, cli.size(), "(device=\"cpu\" or \"auto\")");
      throw sol::NotImplemented("sol.Renderer: " + what);
    }
    notes = std::move(said);
    description = renderer->description();  // (read under the GIL, never while another thread swaps the renderer)
    on_cpu = dynamic_cast<const sol::CpuRenderer*>(renderer.get()) != nullptr;
    camera = scene.camera;
    samples = scene.samples;
  }

  py::dict render(int width, int height, int samples_given, const std::optional<sol::Camera>& eye, const std::string& transport,
                  long long seed, std::optional<double> stereo_ipd, bool aovs, unsigned threads, const py::object& progress,
                  int first_sample, std::optional<double> time_limit, std::optional<double> noise_target, bool denoise) {
    if (seed < 0 || seed > 2147483647LL) {
      throw sol::InvalidArgument("sol.Renderer.render: seed must be in [0, 2^31-1] (solrender's --seed), not " + std::to_string(seed));
    }
    if (stereo_ipd && !(*stereo_ipd >= 0.0 && *stereo_ipd <= 10.0)) {
      throw sol::InvalidArgument("sol.Renderer.render: ipd must be in [0, 10] (solrender's --ipd), not " + std::to_string(*stereo_ipd));
    }
    if (!progress.is_none() && !PyCallable_Check(progress.ptr())) {
      throw sol::InvalidArgument("sol.Renderer.render: progress must be a callable taking the finished fraction, or None");
    }
    sol::RenderOptions options{.width = width,
                               .height = height,
                               .samples = samples_given == 0 ? samples : samples_given,
                               .threads = threads,
                               .transport = transport_named(transport, "sol.Renderer.render"),
                               .seed = static_cast<std::uint64_t>(seed)};
    options.aovs = aovs || denoise;  // (the denoiser's guides)
    options.guides = options.aovs;   // (the dict's albedo, emission and normal)
    options.first_sample = first_sample;
    if (denoise && first_sample != 0) {
      throw sol::InvalidArgument("sol.Renderer.render: denoise takes a render from sample 0 (its AOVs), not first_sample " +
                                 std::to_string(first_sample));
    }
    options.max_dispatch_ms = 100.0;  // as solrender: tiles of about 50 ms, so progress and Ctrl-C are heard
    const sol::Camera from = eye.value_or(camera);
    std::atomic<bool> cancel{false};
    std::optional<py::error_already_set> raised;  // what a handler or the callback raised
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    options.cancel = &cancel;
    options.progress = [&](double fraction) {
      const auto now = std::chrono::steady_clock::now();
      if (cancel.load() || (now - last < std::chrono::milliseconds(100) && fraction < 1.0)) return;
      last = now;
      const py::gil_scoped_acquire gil;
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!progress.is_none()) progress(fraction);
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        cancel.store(true);
      }
    };
    if (first_sample != 0 && (time_limit || noise_target)) {
      throw sol::InvalidArgument("sol.Renderer.render: first_sample or time_limit/noise_target, not both");
    }
    if (time_limit && !(*time_limit > 0.0 && *time_limit <= 1e6)) {
      throw sol::InvalidArgument("sol.Renderer.render: time_limit must be in (0, 1e6] seconds (solrender's --time-limit)");
    }
    if (noise_target && !(*noise_target > 0.0 && *noise_target <= 10.0)) {
      throw sol::InvalidArgument("sol.Renderer.render: noise_target must be in (0, 10] (solrender's --noise-target)");
    }
    sol::RenderResult result;
    std::optional<sol::programs::SamplingReport> batched;
    try {
      py::gil_scoped_release release;
      const std::lock_guard lock(busy);
      const auto once = [&](const sol::RenderOptions& o) {
        return stereo_ipd ? renderer->render_stereo(from, *stereo_ipd, o) : renderer->render(from, o);
      };
      if (!time_limit && !noise_target) {
        result = once(options);
      } else {  // solrender's --time-limit, --noise-target (the progress: each batch's)
        sol::programs::SamplingGoal goal;
        goal.seconds = time_limit;
        goal.noise = noise_target;
        goal.min_samples = options.samples;
        sol::programs::SamplingReport report;
        const auto started = std::chrono::steady_clock::now();
        double shown = 0.0;  // the progress reported, never going back
        result = sol::programs::render_batches(
            [&](int first, int count, bool with_aovs) {
              sol::RenderOptions o = options;
              o.first_sample = first;
              o.samples = count;
              o.aovs = with_aovs;
              o.guides = options.guides;  // (every batch's albedo and emission, joined as the colour)
              // The whole render's progress, not each batch's: the time spent of the limit, else the samples
              // of the most there may be.
              o.progress = [&, first, count](double fraction) {
                const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
                shown = std::max(shown, time_limit ? std::min(1.0, spent / *time_limit)
                                                   : (first + fraction * count) / goal.max_samples);
                options.progress(shown);
              };
              return once(o);
            },
            options.aovs, goal, report);
        batched = report;
      }
    } catch (const sol::Cancelled&) {
      if (raised) throw *raised;
      throw;
    }
    if (raised) throw *raised;  // raised by the last report, after the work was done
    if (denoise) {
      py::gil_scoped_release release;
      const std::lock_guard lock(busy);
      renderer->denoise(result, stereo_ipd ? 2 : 1);
    }
    if (!aovs) {  // (rendered for the denoiser alone)
      for (auto* plane : {&result.object, &result.distance, &result.px, &result.py, &result.pz, &result.steps,
                          &result.albedo, &result.emission, &result.normal, &result.out_of_steps}) {
        plane->clear();
      }
    }
    py::dict out = render_dict(result);
    out["rays_out_of_steps"] = result.rays_out_of_steps;
    out["device_ms"] = result.device_ms;
    if (batched) {
      out["samples"] = batched->samples;
      out["noise"] = batched->noise;
      out["seconds"] = batched->seconds;
    }
    return out;
  }
};
#endif

// The module's exception types (made in PYBIND11_MODULE).
PyObject* g_invalid_argument = nullptr;
PyObject* g_out_of_range = nullptr;
PyObject* g_unsupported = nullptr;

// A new exception type sol.<name> deriving from SolError and `also`.
PyObject* exception_type(py::module_& m, const char* name, PyObject* sol_error, PyObject* also, const char* doc) {
  PyObject* bases = also ? PyTuple_Pack(2, sol_error, also) : PyTuple_Pack(1, sol_error);
  PyObject* type = PyErr_NewExceptionWithDoc((std::string("sol.") + name).c_str(), doc, bases, nullptr);
  Py_DECREF(bases);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module holds a reference for the process's life
  return type;
}

// Raises `type` with a message: its bytes that are not UTF-8 (none are
// meant to be) replaced rather than lost with the whole message.
void set_error(PyObject* type, const char* what) {
  PyObject* text = PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)), "replace");
  if (!text) {
    PyErr_Clear();
    PyErr_SetString(type, "(an undecodable message)");
    return;
  }
  PyErr_SetObject(type, text);
  Py_DECREF(text);
}

// The group law and the geodesics.
#ifdef SOL_PYTHON_IMAGES
// The display of Python's exposure and tone keywords; InvalidArgument naming them.
sol::Display display_of(double exposure, const std::string& tone, const std::string& function) {
  sol::Display d;
  d.exposure = exposure;
  const std::optional<sol::Tone> curve = sol::tone_from_name(tone);
  if (!curve) throw sol::InvalidArgument(function + ": tone must be one of " + sol::tone_names() + ", got '" + tone + "'");
  d.tone = *curve;
  try {
    sol::validate(d);
  } catch (const sol::InvalidArgument& e) {
    throw sol::InvalidArgument(function + ": " + sol::without_function(e.what()));
  }
  return d;
}
#endif

void bind_group_and_geodesics(py::module_& m) {
  // ---- The group
  m.def("multiply", [](const std::array<double, 3>& p, const std::array<double, 3>& q) { return array(sol::multiply(vec3(p), vec3(q))); },
        py::arg("p"), py::arg("q"), "The group law p * q.");
  m.def("inverse", [](const std::array<double, 3>& p) { return array(sol::inverse(vec3(p))); }, py::arg("p"),
        "The group inverse of p.");

  // ---- Geodesics
  m.def(
      "flow",
      [](const std::array<double, 3>& position, const std::array<double, 3>& direction, double t) {
        const sol::GeodesicState s = sol::flow({vec3(position), vec3(direction)}, t);
        return py::make_tuple(array(s.position), array(s.direction));
      },
      py::arg("position"), py::arg("direction"), py::arg("t"),
      "Follows the geodesic from position with direction (frame components, normalised) for arc length t; "
      "returns (end position, end direction).");
  m.def(
      "flow_many",
      [](const std::array<double, 3>& position, const Points& directions, py::array_t<double, py::array::forcecast> t) {
        const std::vector<glm::dvec3> dirs = rows(directions, "directions");
        const py::buffer_info tb = t.request();
        const auto nt = static_cast<std::size_t>(tb.size);
        if (nt != 1 && nt != dirs.size()) throw sol::InvalidArgument("sol.flow_many: t must be a number or one per direction");
        const auto* tv = static_cast<const double*>(tb.ptr);
        std::vector<glm::dvec3> positions(dirs.size()), ends(dirs.size());
        {
          Interrupts interrupts;
          py::gil_scoped_release release;
          for (std::size_t i = 0; i < dirs.size(); ++i) {
            interrupts.check();
            const sol::GeodesicState s = sol::flow({vec3(position), dirs[i]}, tv[nt == 1 ? 0 : i]);
            positions[i] = s.position;
            ends[i] = s.direction;
          }
        }
        return py::make_tuple(rows_array(positions), rows_array(ends));
      },
      py::arg("position"), py::arg("directions"), py::arg("t"),
      "flow for many directions (an (N, 3) array) from one position, t one number or one per direction; "
      "returns ((N, 3) end positions, (N, 3) end directions).");
  m.def(
      "transport",
      [](const std::array<double, 3>& position, const std::array<double, 3>& direction, double t) {
        const glm::dmat3 q = sol::transport({vec3(position), vec3(direction)}, t);
        py::array_t<double> out({py::ssize_t{3}, py::ssize_t{3}});
        auto o = out.mutable_unchecked<2>();
        for (py::ssize_t r = 0; r < 3; ++r) {
          for (py::ssize_t c = 0; c < 3; ++c) o(r, c) = q[static_cast<glm::length_t>(c)][static_cast<glm::length_t>(r)];
        }
        return out;
      },
      py::arg("position"), py::arg("direction"), py::arg("t"),
      "The parallel-transport matrix along the geodesic: column i holds the frame components at the end of "
      "the frame vector E_i at the start, transported.");
}

// Distances, connections and the shapes.
void bind_distances_and_shapes(py::module_& m) {
  // ---- Distances and connections
  m.def("distance", [](const std::array<double, 3>& p, const std::array<double, 3>& q) { return sol::distance(vec3(p), vec3(q)); },
        py::arg("p"), py::arg("q"), "The exact Sol distance from p to q.");
  m.def(
      "distances",
      [](const std::array<double, 3>& p, const Points& points) {
        const std::vector<glm::dvec3> qs = rows(points, "points");
        py::array_t<double> out(static_cast<py::ssize_t>(qs.size()));
        auto o = out.mutable_unchecked<1>();
        std::vector<double> d(qs.size());
        {
          Interrupts interrupts;
          py::gil_scoped_release release;
          for (std::size_t i = 0; i < qs.size(); ++i) {
            interrupts.check();
            d[i] = sol::distance(vec3(p), qs[i]);
          }
        }
        for (std::size_t i = 0; i < d.size(); ++i) o(static_cast<py::ssize_t>(i)) = d[i];
        return out;
      },
      py::arg("p"), py::arg("points"), "The distances from p to each row of an (N, 3) array.");
  m.def("minimising_geodesics",
        [](const std::array<double, 3>& p, const std::array<double, 3>& q) { return connections(sol::minimising_geodesics(vec3(p), vec3(q))); },
        py::arg("p"), py::arg("q"),
        "The shortest geodesics from p to q (one, or two on the cut locus) as a list of (unit direction at p, length).");
  m.def("geodesics_between",
        [](const std::array<double, 3>& p, const std::array<double, 3>& q, double max_length) {
          return connections(sol::geodesics_between(vec3(p), vec3(q), max_length));
        },
        py::arg("p"), py::arg("q"), py::arg("max_length"),
        "Every geodesic from p to q of length up to max_length, shortest first, as (unit direction at p, length).");
  m.def(
      "aim",
      [](const std::array<double, 3>& eye, const std::array<double, 3>& target, const std::optional<sol::Lattice>& lattice) {
        const sol::Aim a = sol::aim(vec3(eye), vec3(target), lattice);
        py::dict d;
        d["direction"] = array(a.direction);
        d["distance"] = a.distance;
        d["end"] = array(a.end);
        d["cut_locus"] = a.cut_locus;
        return d;
      },
      py::arg("eye"), py::arg("target"), py::arg("lattice") = py::none(),
      "The minimising geodesic from eye to target (in the quotient of `lattice`: to the target's nearest image), "
      "as a dict: direction (unit, frame components at the eye: a camera's forward that puts the target at the "
      "image's centre), distance, end (the target or the image reached, in the eye's coordinates) and cut_locus "
      "(another minimiser of the same length exists; the upward one is taken). A scene's camera takes it as "
      "camera={\"look_at\": target}.");
  m.def(
      "lens_ray",
      [](const sol::Camera& camera, const std::array<double, 3>& direction, const std::array<double, 2>& disk) {
        const sol::LensRay r = sol::lens_ray(camera, glm::normalize(vec3(direction)), {disk[0], disk[1]});
        py::dict d;
        d["start"] = array(r.start);
        d["direction"] = array(r.direction);
        d["focus_length"] = r.focus_length;
        d["focused"] = r.focused;
        return d;
      },
      py::arg("camera"), py::arg("direction"), py::arg("disk"),
      "Depth of field: the ray of the camera's lens through the point `disk` of the unit disk for the pixel ray "
      "`direction` (frame components), as a dict: start (the lens point, in the eye's coordinates), direction (unit, "
      "frame components there), focus_length (the arc length to the focus point) and focused (false where no "
      "such ray was found near the pixel ray's). Renders take lens point sol.lens_sample(k) for sample k.");
  m.def(
      "lens_sample",
      [](int k) {
        const glm::dvec2 p = sol::lens_sample(k);
        return std::array<double, 2>{p.x, p.y};
      },
      py::arg("k"),
        "The k-th lens sample, a point (x, y) of the unit disk; sample 0 is its centre.");
  m.def("sphere_area_density",
        [](const std::array<double, 3>& direction, double t) { return sol::sphere_area_density(vec3(direction), t); },
        py::arg("direction"), py::arg("t"),
        "J(v, t): the area of the geodesic sphere of radius t per unit solid angle at the direction (docs/lighting.md).");

  // ---- Shapes
  m.def(
      "geodesic_sphere",
      [](const std::array<double, 3>& center, double radius, int subdivisions) {
        sol::Mesh mesh;
        {
          py::gil_scoped_release release;  // up to 8 x 512^2 triangles: seconds
          mesh = sol::geodesic_sphere(vec3(center), radius, subdivisions);
        }
        py::array_t<int> triangles({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
        auto t = triangles.mutable_unchecked<2>();
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
          for (py::ssize_t c = 0; c < 3; ++c) t(static_cast<py::ssize_t>(i), c) = mesh.triangles[i][static_cast<std::size_t>(c)];
        }
        return py::make_tuple(rows_array(mesh.vertices), triangles);
      },
      py::arg("center"), py::arg("radius"), py::arg("subdivisions") = 32,
      "A closed, outward-oriented triangle mesh of the geodesic sphere about center (radius up to 6; from sqrt(2) pi "
      "on with its creases on the cut locus): ((N, 3) vertices in Sol coordinates, (M, 3) vertex indices).");
  m.def(
      "cut_time", [](const std::array<double, 3>& direction) { return sol::cut_time(vec3(direction)); }, py::arg("direction"),
      "Where the geodesic from the origin with this direction stops minimising: its z-period (inf for the planes' "
      "and the vertical geodesics).");
  m.def(
      "geodesic_polylines",
      [](const std::array<double, 3>& from, const Points& directions, double length, int segments) {
        const std::vector<glm::dvec3> dirs = rows(directions, "directions");
        sol::check_polyline_points(dirs.size(), segments, "sol.geodesic_polylines");  // the whole, before the parts
        // A direction at a time (the checks of the arguments with the first),
        // Ctrl-C heard between them.
        std::vector<std::vector<glm::dvec3>> lines;
        {
          Interrupts interrupts;
          py::gil_scoped_release release;
          for (std::size_t i = 0; i < std::max<std::size_t>(dirs.size(), 1); ++i) {
            interrupts.check();
            const std::vector<glm::dvec3> one = dirs.empty() ? dirs : std::vector<glm::dvec3>{dirs[i]};
            for (auto& line : sol::geodesic_polylines(vec3(from), one, length, segments)) lines.push_back(std::move(line));
          }
        }
        py::list out;
        for (const auto& line : lines) out.append(rows_array(line));
        return out;
      },
      py::arg("start"), py::arg("directions"), py::arg("length"), py::arg("segments") = 100,
      "Geodesics from start along each direction (an (N, 3) array or one (3,)) to arc length `length`: a list of (segments + 1, 3) "
      "arrays of points evenly spaced in arc length.");
  m.def(
      "cut_locus_curves",
      [](const std::array<double, 3>& center, const std::vector<double>& radii, int samples) {
        sol::check_cut_locus_points(radii.size(), samples, "sol.cut_locus_curves");  // the whole, before the parts
        // A radius at a time, Ctrl-C heard between them.
        std::vector<std::vector<glm::dvec3>> curves;
        {
          Interrupts interrupts;
          py::gil_scoped_release release;
          for (std::size_t i = 0; i < std::max<std::size_t>(radii.size(), 1); ++i) {
            interrupts.check();
            const std::vector<double> one = radii.empty() ? radii : std::vector<double>{radii[i]};
            for (auto& curve : sol::cut_locus_curves(vec3(center), one, samples)) curves.push_back(std::move(curve));
          }
        }
        py::list out;
        for (const auto& curve : curves) out.append(rows_array(curve));
        return out;
      },
      py::arg("center"), py::arg("radii"), py::arg("samples") = 64,
      "The cut locus of center where it meets the spheres of the given radii (in (sqrt(2) pi, 6]): four (samples, 3) "
      "arcs per radius, each point with two minimising geodesics.");
}

// The lattice.
void bind_lattice(py::module_& m) {
  // ---- The lattice
  py::class_<sol::Lattice>(m, "Lattice",
                           "A lattice Γ of Sol, whose compact quotient Γ\\Sol is the torus bundle of a hyperbolic "
                           "monodromy A (docs/mathematics.md, 'Every lattice').")
      .def(py::init([](const std::array<std::array<long long, 2>, 2>& a, std::optional<double> fibre_area) {
             return sol::Lattice::from_monodromy({a[0][0], a[0][1], a[1][0], a[1][1]}, fibre_area);
           }),
           py::arg("monodromy"), py::arg("fibre_area") = py::none(),
           "The lattice of the monodromy [[a, b], [c, d]] (in SL(2, Z), |trace| > 2; a negative trace turns the fibre), "
           "its fibre torus of area "
           "`fibre_area` (None: the normalisation u+.e2 = 1, u-.e1 = -1, which for [[2, 1], [1, 1]] is the golden "
           "lattice).")
      .def_static("golden", &sol::Lattice::golden, "The golden lattice, of [[2, 1], [1, 1]].")
      .def_static("z_loop", &sol::Lattice::z_loop, py::arg("height"),
                  "The loop γ3 = (0, 0, height) alone (height in [1, 20]): the non-compact quotient Sol/<γ3>, whose "
                  "domain is R^2 x [0, height) (docs/mathematics.md, 'The non-compact quotients').")
      .def_static(
          "xy_loops",
          [](const std::array<double, 2>& g1, const std::array<double, 2>& g2) {
            return sol::Lattice::xy_loops({g1[0], g1[1]}, {g2[0], g2[1]});
          },
          py::arg("gamma1"), py::arg("gamma2"),
          "The loops γ1 = (x1, y1, 0) and γ2 = (x2, y2, 0) alone: the quotient Sol/<γ1, γ2>, a torus times a line, "
          "whose domain is their parallelogram times every height.")
      .def_property_readonly(
          "loops",
          [](const sol::Lattice& l) {
            switch (l.loops()) {
              case sol::Lattice::Loops::Z:
                return "z";
              case sol::Lattice::Loops::XY:
                return "xy";
              case sol::Lattice::Loops::All:
                break;
            }
            return "all";
          },
          "Which loops the quotient closes: 'all' (a compact torus bundle), 'z' (a z loop) or 'xy' (xy loops).")
      .def_property_readonly(
          "monodromy",
          [](const sol::Lattice& l) {
            const sol::Monodromy& a = l.monodromy();
            return py::make_tuple(py::make_tuple(a.a, a.b), py::make_tuple(a.c, a.d));
          },
          "The monodromy A: conjugation by γ3 acts on the words γ1^a γ2^b as A.")
      .def_property_readonly(
          "generators",
          [](const sol::Lattice& l) {
            const auto& g = l.generators();
            return py::make_tuple(array(g[0]), array(g[1]), array(g[2]));
          },
          "γ1, γ2, γ3 as points of Sol.")
      .def_property_readonly("fibre_area", &sol::Lattice::fibre_area, "The area |det(γ1, γ2)| of the fibre torus.")
      .def_property_readonly("turns", &sol::Lattice::turns,
                             "Whether γ3 also turns the fibre by the half-turn (x, y, z) -> (-x, -y, z) (trace < -2).")
      .def(
          "apply",
          [](const sol::Lattice& l, const std::array<long long, 3>& w, const std::array<double, 3>& p) {
            return array(l.apply({w[0], w[1], w[2]}, vec3(p)));
          },
          py::arg("word"), py::arg("p"), "The image of p under the word (a, b, c)'s isometry.")
      .def_property_readonly("height", &sol::Lattice::height, "The height of the fundamental domain D: ln λ.")
      .def(
          "multiply",
          [](const sol::Lattice& l, const std::array<long long, 3>& u, const std::array<long long, 3>& v) {
            const sol::LatticeWord w = l.multiply({u[0], u[1], u[2]}, {v[0], v[1], v[2]});
            return py::make_tuple(w.a, w.b, w.c);
          },
          py::arg("u"), py::arg("v"), "The product of the words u = (a, b, c) and v (γ1^a γ2^b γ3^c) in normal form.")
      .def("__repr__",
           [](const sol::Lattice& l) {
             const auto& g = l.generators();
             switch (l.loops()) {
               case sol::Lattice::Loops::Z:
                 return "sol.Lattice.z_loop(" + std::to_string(l.height()) + ")";
               case sol::Lattice::Loops::XY:
                 return "sol.Lattice.xy_loops((" + std::to_string(g[0].x) + ", " + std::to_string(g[0].y) + "), (" +
                        std::to_string(g[1].x) + ", " + std::to_string(g[1].y) + "))";
               case sol::Lattice::Loops::All:
                 break;
             }
             return "sol.Lattice(" + l.monodromy().str() + ")";
           })
      .def(
          "element", [](const sol::Lattice& l, long long a, long long b, long long c) { return array(l.element(a, b, c)); },
          py::arg("a"), py::arg("b"), py::arg("c"), "The group element γ1^a γ2^b γ3^c as a point.")
      .def("contains", [](const sol::Lattice& l, const std::array<double, 3>& p) { return l.contains(vec3(p)); }, py::arg("p"),
           "Whether p lies in the fundamental domain D.")
      .def(
          "teleport",
          [](const sol::Lattice& l, const std::array<double, 3>& p) {
            const sol::Teleport t = l.teleport(vec3(p));
            const sol::LatticeWord w = l.word_of(t.element);
            return py::make_tuple(array(t.point), py::make_tuple(w.a, w.b, w.c));
          },
          py::arg("p"), "The point of D equivalent to p and the word (a, b, c) of the element taking p there.");
}

// Scenes and the CPU renderer.
void bind_scenes(py::module_& m) {
  // ---- Scenes and the CPU renderer
  py::class_<sol::Camera>(m, "Camera",
                          "A camera (make one with sol.camera(...), or take a scene's: scene.camera): where it is, "
                          "where it looks, how pixels map to directions (docs/scene-format.md).")
      .def_property_readonly("position", [](const sol::Camera& c) { return array(c.position); },
                             "Sol coordinates (x, y, z).")
      .def_property_readonly("forward", [](const sol::Camera& c) { return array(c.forward); },
                             "The view direction, frame components.")
      .def_property_readonly("up", [](const sol::Camera& c) { return array(c.up); }, "Up, frame components.")
      .def_property_readonly("fov", [](const sol::Camera& c) { return c.fov; },
                             "The vertical field of view, degrees (perspective).")
      .def_property_readonly("aperture", [](const sol::Camera& c) { return c.aperture; },
                             "Depth of field: the thin lens's radius, an arc length (0: a pinhole; sol.lens_ray).")
      .def_property_readonly("focus_distance", [](const sol::Camera& c) { return c.focus_distance; },
                             "The arc length along each pixel's geodesic that is in focus.")
      .def("__repr__", [](const sol::Camera& c) {
        char text[200];
        std::snprintf(text, sizeof text, "sol.Camera(position=(%g, %g, %g), forward=(%g, %g, %g), fov=%g)", c.position.x,
                      c.position.y, c.position.z, c.forward.x, c.forward.y, c.forward.z, c.fov);
        return std::string(text);
      });
  py::class_<sol::Scene>(m, "Scene",
                         "A scene: camera, objects, lights and the world's settings (docs/scene-format.md). Make one "
                         "with sol.scene(...) or a preset, change it with scene.replace(...).")
      .def("to_json", [](const sol::Scene& s) { return sol::to_json(s); }, "The scene as JSON text (a scene file).")
      .def_property_readonly("camera", [](const sol::Scene& s) { return s.camera; }, "The scene's camera (a copy).")
      .def_property_readonly("camera_position", [](const sol::Scene& s) { return array(s.camera.position); },
                             "The camera's position, Sol coordinates.")
      .def_property_readonly("object_count", [](const sol::Scene& s) { return s.objects.size(); },
                             "How many objects the scene has.");
  m.def(
      "_scene_with_camera",
      [](const sol::Camera& camera) {
        sol::Scene s;
        s.camera = camera;
        return s;
      },
      py::arg("camera"), "(sol.scenes: a camera's fields as a scene file writes them.)");
  m.def("preset_names", &sol::preset_names, "The names of the built-in scenes.");
  m.def("preset_scene", [](const std::string& name) { return sol::preset_scene(name); }, py::arg("name"),
        "A built-in scene by name.");
  m.def("load_scene", &sol::load_scene, py::arg("path"), "A scene file.");
  m.def(
      "camera_rays",
      [](const sol::Scene& scene, int width, int height) {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) {
          throw sol::InvalidArgument("sol.camera_rays: width and height must be in [1, 16384]");
        }
        py::array_t<double> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), py::ssize_t{3}});
        auto o = out.mutable_unchecked<3>();
        for (int j = 0; j < height; ++j) {
          for (int i = 0; i < width; ++i) {
            const glm::dvec3 d = sol::camera_ray(scene.camera, i, j, width, height);
            for (py::ssize_t c = 0; c < 3; ++c) o(j, i, c) = d[static_cast<glm::length_t>(c)];
          }
        }
        return out;
      },
      py::arg("scene"), py::arg("width"), py::arg("height"),
      "The unit direction (frame components at the camera) of the ray through each pixel's centre, as render_cpu "
      "shoots it: an (H, W, 3) array.");
  m.def("parse_scene", [](const std::string& text, const std::string& source) { return sol::parse_scene(text, source); },
        py::arg("text"), py::arg("source") = "<scene>",
        "A scene from JSON text (a scene file's); errors name `source` and the field.");
  py::class_<PyCpuRenderer>(m, "CpuRenderer",
                            "The CPU reference renderer with a scene's world prepared once (validation, features, the "
                            "quotient's images): every render() then reuses it, from the scene's camera.")
      .def(py::init([](const sol::Scene& scene) {
             auto r = std::make_unique<PyCpuRenderer>();
             r->set_scene(scene);
             return r;
           }),
           py::arg("scene"), "Prepares the scene's world.")
      .def("set_scene", &PyCpuRenderer::set_scene, py::arg("scene"), "Prepares another scene's world (and takes its camera).")
      .def(
          "render",
          [](PyCpuRenderer& r, int width, int height, int samples, unsigned threads, const std::optional<sol::Camera>& camera,
             const std::string& transport, long long seed) {
            return render_dict(r.render(width, height, samples, threads, camera, transport, seed));
          },
          py::arg("width") = 512, py::arg("height") = 512, py::arg("samples") = 0, py::arg("threads") = 0,
          py::arg("camera") = py::none(), py::arg("transport") = "direct", py::arg("seed") = 0,
          "Renders the prepared world, width x height pixels (1..16384; solrender's 512 x 512 by default), from "
          "`camera` (a sol.Camera; the scene's when None), `samples` rays per pixel (1..4096; 0: the scene's "
          "\"samples\", as solrender's --spp), on `threads` threads (0: all), by `transport` (\"direct\" light, the "
          "default, or \"path\" tracing, each sample one path whose random numbers come from `seed`, 0 or more, as "
          "solrender's --transport and --seed): a dict of float32 arrays as render_cpu's.");
#ifdef SOL_PYTHON_IMAGES
  py::class_<PyRenderer>(m, "_Renderer", "(sol.Renderer: the renderer of either device.)")
      .def(py::init([](const sol::Scene& scene, const std::string& device, const std::string& transport, bool rk4,
                       double rk4_step) {
             auto r = std::make_unique<PyRenderer>();
             r->choice.device = PyRenderer::device_named(device);
             r->choice.transport = transport_named(transport, "sol.Renderer");
             if (!(rk4_step > 0.0 && rk4_step <= 1.0)) {
               throw sol::InvalidArgument("sol.Renderer: rk4_step must be in (0, 1], not " + std::to_string(rk4_step));
             }
             r->choice.rk4 = rk4;
             r->choice.rk4_step = rk4_step;
             r->set_scene(scene);
             return r;
           }),
           py::arg("scene"), py::arg("device"), py::arg("transport"), py::arg("rk4"), py::arg("rk4_step"))
      .def("set_scene", &PyRenderer::set_scene, py::arg("scene"))
      .def("render", &PyRenderer::render, py::arg("width"), py::arg("height"), py::arg("samples"), py::arg("camera"),
           py::arg("transport"), py::arg("seed"), py::arg("ipd"), py::arg("aovs"), py::arg("threads"), py::arg("progress"),
           py::arg("first_sample"), py::arg("time_limit"), py::arg("noise_target"), py::arg("denoise"))
      .def_property_readonly("description", [](const PyRenderer& r) { return r.description; })
      .def_property_readonly("device", [](const PyRenderer& r) { return r.on_cpu ? "cpu" : "vulkan"; })
      .def_property_readonly("notes", [](const PyRenderer& r) { return r.notes; });
#endif
  m.def("has_vulkan",
        []() {
#ifdef SOL_PYTHON_IMAGES
          return sol::programs::has_vulkan();
#else
          return false;
#endif
        },
        "Whether this sol has the Vulkan kernel (sol.Renderer(device=\"vulkan\")); sol.vulkan_missing() says what its "
        "build lacked when it has not.");
  m.def("vulkan_missing", []() { return std::string(sol_vulkan_missing()); },
        "What the build lacked for the Vulkan kernel, for people (\"\" when it has it or was built without asking).");
  m.def(
      "render_cpu",
      [](const sol::Scene& scene, int width, int height, int samples, unsigned threads, const std::optional<sol::Camera>& camera,
         const std::string& transport, long long seed) {
        PyCpuRenderer r;
        r.set_scene(scene);
        return render_dict(r.render(width, height, samples, threads, camera, transport, seed));
      },
      py::arg("scene"), py::arg("width") = 512, py::arg("height") = 512, py::arg("samples") = 0, py::arg("threads") = 0,
      py::arg("camera") = py::none(), py::arg("transport") = "direct", py::arg("seed") = 0,
      "Renders the scene on the CPU, preparing its world for this one render (CpuRenderer keeps it for many), with "
      "CpuRenderer.render's arguments and defaults; returns a dict of float32 arrays: rgba (H, W, 4; linear RGB, "
      "alpha 1: sol.save writes it as solrender does), object (H, W; 0 = no hit, k = k-th object), distance (H, W; "
      "arc length to the hit), point (H, W, 3; Sol coordinates of the hit), steps (H, W; march steps), albedo (H, W, 3; "
      "the samples' mean), emission (H, W, 3; what the hits emit towards the eye, the samples' mean) and normal (H, W, 3; "
      "the centre's, frame components, facing the ray).");
#ifdef SOL_PYTHON_IMAGES
  m.def(
      "save",
      [](const std::string& path, const py::array_t<float, py::array::c_style | py::array::forcecast>& image,
         double exposure, const std::string& tone) {
        const sol::Display display = display_of(exposure, tone, "sol.save");
        const py::buffer_info b = image.request();
        if (b.ndim != 3 || (b.shape[2] != 3 && b.shape[2] != 4)) {
          throw sol::InvalidArgument("sol.save: image must have shape (H, W, 3) or (H, W, 4), RGB(A) linear");
        }
        const auto height = static_cast<int>(b.shape[0]), width = static_cast<int>(b.shape[1]);
        const auto channels = static_cast<std::size_t>(b.shape[2]);
        const auto* data = static_cast<const float*>(b.ptr);
        std::vector<float> pixels(data, data + static_cast<std::size_t>(b.size));
        std::vector<std::string> names{"R", "G", "B"};
        if (channels == 4) names.push_back("A");
        std::size_t non_finite = 0;
        {
          py::gil_scoped_release release;
          try {
            non_finite = sol::programs::write_image(path, width, height, names, pixels, true, display);
          } catch (const std::runtime_error& e) {
            throw sol::InvalidArgument(std::string("sol.save: ") + e.what());
          }
        }
        return non_finite;
      },
      py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0, py::arg("tone") = "clamp",
      "Writes a linear RGB(A) image ((H, W, 3|4), a render's 'rgba') to `path` with solrender's writer: the format "
      "from the extension (png, jpg, exr, tif, hdr, ...), 8-bit formats through the exposure (stops) and the tone "
      "curve (\"clamp\" or \"aces\", solrender's --exposure and --tone) and sRGB-encoded, float ones linear "
      "whatever those say; complete or not at all. Returns how many values were not finite (written as 0).");
  m.def(
      "srgb8",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& image, double exposure,
         const std::string& tone) {
        const sol::Display display = display_of(exposure, tone, "sol.srgb8");
        const int curve = static_cast<int>(display.tone);
        const double scale = display.scale();
        const py::buffer_info b = image.request();
        std::vector<py::ssize_t> shape(b.shape.begin(), b.shape.end());
        py::array_t<std::uint8_t> out(shape);
        const auto* in = static_cast<const float*>(b.ptr);
        auto* o = out.mutable_data();
        const bool rgba = b.ndim == 3 && b.shape[2] == 4;
        for (py::ssize_t i = 0; i < b.size; ++i) {
          o[i] = rgba && i % 4 == 3 ? static_cast<std::uint8_t>(std::lround(std::clamp(in[i], 0.0f, 1.0f) * 255.0f))
                                    : sol::programs::display_byte(std::isfinite(in[i]) ? in[i] : 0.0f, curve, scale);
        }
        return out;
      },
      py::arg("image"), py::arg("exposure") = 0.0, py::arg("tone") = "clamp",
      "A linear image as the 8-bit bytes solrender writes with the same --exposure (stops) and --tone (\"clamp\" or "
      "\"aces\"): scaled by 2^exposure, through the tone curve, sRGB-encoded (alpha of an (H, W, 4) image scaled, "
      "not encoded); a uint8 array of the same shape.");
#endif
}

}  // namespace

PYBIND11_MODULE(_sol, m) {
#ifdef SOL_PYTHON_IMAGES
  sol::programs::install_texture_reader();  // scene files' and sol.scene's "texture" keys
#endif
  m.doc() = "libsol: Thurston's Sol geometry (group law, geodesics, distances, the lattice, scenes, the CPU renderer)";
  // Errors: all sol.SolError, and the builtin a caller may already catch
  // (names that shadow no builtin under `from sol import *`).
  PyObject* sol_error = PyErr_NewExceptionWithDoc("sol.SolError", "Every error sol raises.", PyExc_Exception, nullptr);
  if (!sol_error) throw py::error_already_set();
  m.add_object("SolError", py::handle(sol_error));
  g_invalid_argument = exception_type(m, "InvalidArgumentError", sol_error, PyExc_ValueError,
                                      "An argument or a scene field out of its domain; the message names it.");
  g_out_of_range = exception_type(m, "OutOfRangeError", sol_error, PyExc_ValueError,
                                  "A result beyond what double (or the renderer) can represent, or work beyond its bounds.");
  g_unsupported = exception_type(m, "UnsupportedError", sol_error, PyExc_NotImplementedError,
                                 "Something libsol does not do (yet).");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sol::InvalidArgument& e) {
      set_error(g_invalid_argument, e.what());
    } catch (const sol::OutOfRange& e) {
      set_error(g_out_of_range, e.what());
    } catch (const sol::NotImplemented& e) {
      set_error(g_unsupported, e.what());
    } catch (const sol::Cancelled& e) {
      set_error(PyExc_KeyboardInterrupt, e.what());
    }
  });
  m.attr("__version__") = SOL_VERSION_STRING;

  bind_group_and_geodesics(m);
  bind_distances_and_shapes(m);
  bind_lattice(m);
  bind_scenes(m);
}
