// solxr through the headless OpenXR test runtime (xr/test_runtime/), loaded
// by the real OpenXR loader (XR_RUNTIME_JSON), on lavapipe with the Vulkan
// validation layer on: eye images against the CPU reference renderer for
// the eyes the head poses give, head motion, locomotion, the session's life
// cycle and leaks, and the failures (no runtime, no Vulkan support, no
// headset, bad options).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <sol/sol.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "eye_pose.hpp"

namespace {

namespace fs = std::filesystem;

struct SolxrRun {
  int exit_code = -1;
  std::string err;  // stderr and stdout
  fs::path dir;     // the script, the log and the saved eye images
};

/// Runs solxr with `args` against the test runtime playing `script` (JSON,
/// without the "output" key, which is added). A fresh directory per call.
SolxrRun run_solxr(const std::string& name, const std::string& script, const std::string& args,
                   const std::string& runtime_json = SOL_XR_TEST_RUNTIME_JSON) {
  SolxrRun r;
  r.dir = fs::path(SOL_XR_TEST_DIR) / name;
  fs::remove_all(r.dir);
  fs::create_directories(r.dir);
  std::string body = script;
  const std::size_t brace = body.find('{');
  body.insert(brace + 1, "\"output\": \"" + r.dir.string() + "\", ");
  std::ofstream(r.dir / "script.json") << body;
  const fs::path log = r.dir / "log.txt";
  // Every run goes through the OpenXR core validation layer (Debian
  // openxr-layer-corevalidation), which prints what it finds on stdout.
  // The render scale fixed unless the test is about it: the eye images are
  // compared with full-size CPU renders, whatever the machine's speed.
  const std::string scale = args.find("--adaptive") == std::string::npos ? "--adaptive off " : "";
  const std::string command = "XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation XR_RUNTIME_JSON='" +
                              runtime_json + "' SOLXR_TEST_SCRIPT='" +
                              (r.dir / "script.json").string() + "' '" SOLXR_PATH "' --validation " + scale + args +
                              " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::stringstream text;
  text << std::ifstream(log).rdbuf();
  r.err = text.str();
  return r;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A clean run: exit 0, the runtime saw every object destroyed, no Vulkan
/// validation message, and the OpenXR core validation layer loaded and
/// silent (its messages begin "[VALID_ERROR |" or "[VALID_WARNING |").
void expect_clean(const SolxrRun& r) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "Core Validation output type")) << r.err;
  EXPECT_FALSE(contains(r.err, "[VALID_")) << r.err;
  EXPECT_TRUE(contains(r.err, " 0 objects leaked")) << r.err;
  EXPECT_FALSE(contains(r.err, "LEAK")) << r.err;
  EXPECT_FALSE(contains(r.err, "validation error")) << r.err;
  EXPECT_FALSE(contains(r.err, "validation warning")) << r.err;  // performance warnings too (a blit from GENERAL)
}

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;
};

/// A saved eye image (the runtime's "image_format": EXR, linear, or PNG,
/// 8-bit sRGB, decoded here to linear by the sRGB curve) as linear RGBA.
Image load_eye(const fs::path& dir, int frame, int view, const std::string& format = "exr") {
  Image image;
  const fs::path path = dir / ("frame" + std::to_string(frame) + "_view" + std::to_string(view) + "." + format);
  const auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
    return image;
  }
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  EXPECT_EQ(spec.nchannels, 4) << path;
  image.rgba.resize(static_cast<std::size_t>(image.width) * image.height * 4);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, image.rgba.data())) << path << ": " << in->geterror();
  if (format == "png") {
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
      if (i % 4 == 3) continue;
      const double c = image.rgba[i];
      image.rgba[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
  }
  return image;
}

/// Pixels whose colour differs by more than `tolerance` in some channel.
int differing_pixels(const Image& xr, const sol::RenderResult& cpu, float tolerance) {
  EXPECT_EQ(xr.width, cpu.width);
  EXPECT_EQ(xr.height, cpu.height);
  if (xr.rgba.size() != cpu.rgba.size()) return xr.width * xr.height;
  int differs = 0;
  for (std::size_t k = 0; k < xr.rgba.size() / 4; ++k) {
    bool d = false;
    for (int c = 0; c < 3; ++c) d = d || !(std::abs(xr.rgba[4 * k + c] - cpu.rgba[4 * k + c]) <= tolerance);
    differs += d;
  }
  return differs;
}

sol::RenderResult cpu_render(sol::Scene scene, const sol::Camera& eye, int width, int height) {
  scene.camera = eye;
  sol::RenderOptions settings;
  settings.width = width;
  settings.height = height;
  return sol::render_cpu(scene, settings);
}

// The kernel renders in float, the CPU reference in double: as in
// kernel_test.cpp, a pixel counts as equal within 2e-3 per channel (float
// rounding of the shading), and up to 2% of the pixels may differ (rays
// grazing an edge or a pattern border land on one side in float and on the
// other in double: kernel_test allows 1% mask and 1% colour flips). 8-bit
// sRGB swapchains add half a quantisation step, 0.5/255 in sRGB, which is at
// most 0.5/255 · 2.4/1.055 ≈ 4.5e-3 in linear units (the decoding's steepest
// slope, at 1): 7e-3 covers both.
constexpr float kFloatTolerance = 2e-3f, kSrgbTolerance = 7e-3f;
int allowed(const Image& image) { return image.width * image.height / 50; }

sol::Scene plane_with_fov(double fov) {
  sol::Scene scene = sol::preset_scene("plane");
  scene.camera.fov = fov;
  return scene;
}

// --- the pose mapping alone ---

TEST(XrEyePose, EyesAtHalfTheIpdAreTheStereoEyes) {
  const sol::Scene scene = plane_with_fov(70);
  const sol::Observer base(scene.camera.position, scene.camera.forward, scene.camera.up);
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.3);
  const sol::Camera left = sol::xr::eye_camera(base, {{-0.15, 0, 0}, {1, 0, 0, 0}}, 1.0, scene.camera);
  const sol::Camera right = sol::xr::eye_camera(base, {{0.075, 0, 0}, {1, 0, 0, 0}}, 2.0, scene.camera);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(left.position[i], eyes.left.position[i], 1e-12);
    EXPECT_NEAR(right.position[i], eyes.right.position[i], 1e-12);
    EXPECT_NEAR(left.forward[i], eyes.left.forward[i], 1e-10);
    EXPECT_NEAR(right.up[i], eyes.right.up[i], 1e-10);
  }
  const sol::Camera still = sol::xr::eye_camera(base, {}, 1.0, scene.camera);
  const sol::CameraBasis b = sol::camera_basis(scene.camera);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(still.position[i], scene.camera.position[i]);
    EXPECT_NEAR(still.forward[i], b.forward[i], 1e-15);
    EXPECT_NEAR(still.up[i], b.up[i], 1e-15);
  }
}

TEST(XrEyePose, TranslationIsTheGeodesicOfThatLengthAndRotationTurnsTheEye) {
  const sol::Observer base({0.2, -0.1, 0.7}, {1, 0.3, 0.2}, {0, 0, 1});
  // OpenXR: a head 0.5 m forward (-z) and 0.2 m up, turned 90° left (about +y).
  const glm::dquat left90 = glm::angleAxis(M_PI / 2, glm::dvec3(0, 1, 0));
  const sol::Camera eye = sol::xr::eye_camera(base, {{0, 0.2, -0.5}, left90}, 1.0, sol::Camera{});
  const glm::dvec3 d = 0.2 * base.up() + 0.5 * base.forward();
  const double length = glm::length(d);
  const sol::GeodesicState end = sol::flow({base.position(), d / length}, length);
  const glm::dmat3 q = sol::transport({base.position(), d / length}, length);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(eye.position[i], end.position[i], 1e-12);
    // Turned left: the eye looks along the transported -right, up unchanged.
    EXPECT_NEAR(eye.forward[i], -(q * base.right())[i], 1e-9);
    EXPECT_NEAR(eye.up[i], (q * base.up())[i], 1e-9);
  }
}

// --- solxr through the test runtime ---

TEST(XrSolxr, EachEyeImageIsTheCpuRenderOfThatEye) {
  const SolxrRun r = run_solxr(
      "stereo", R"({"width": 32, "height": 32, "fov": 60, "ipd": 0.2, "frames": [{}, {}, {}]})", "--scene plane");
  expect_clean(r);
  EXPECT_TRUE(contains(r.err, "3 frames ended, 6 images saved")) << r.err;
  const sol::Scene scene = plane_with_fov(60);
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.2);
  const sol::RenderResult left = cpu_render(scene, eyes.left, 32, 32), right = cpu_render(scene, eyes.right, 32, 32);
  for (int frame = 0; frame < 3; ++frame) {
    const Image l = load_eye(r.dir, frame, 0), rr = load_eye(r.dir, frame, 1);
    EXPECT_LE(differing_pixels(l, left, kFloatTolerance), allowed(l)) << "frame " << frame;
    EXPECT_LE(differing_pixels(rr, right, kFloatTolerance), allowed(rr)) << "frame " << frame;
  }
  // The eyes see different images (the test has teeth).
  EXPECT_GT(differing_pixels(load_eye(r.dir, 0, 0), right, kFloatTolerance), allowed(load_eye(r.dir, 0, 0)));
}

// A still head refines (--refine 4): from 0.25 s of still views (frame 23
// at the runtime's 90 Hz) four jittered samples join a running mean, then
// that image is shown again; the last frame is the CPU render with 4
// samples per pixel (the same pixel_sample sequence), an early one the
// single-sample render, and the two differ (the test has teeth).
TEST(XrSolxr, AStillHeadRefinesToTheSampledMean) {
  std::string frames;
  for (int k = 0; k < 36; ++k) frames += k == 0 ? "{}" : ", {}";
  const SolxrRun r = run_solxr("refine", R"({"width": 16, "height": 16, "fov": 60, "ipd": 0.2, "frames": [)" + frames + "]}",
                               "--scene sandwich --refine 4");
  expect_clean(r);
  sol::Scene scene = sol::preset_scene("sandwich");
  scene.camera.fov = 60.0;
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.2);
  sol::Scene one = scene;
  one.camera = eyes.left;
  sol::RenderOptions settings;
  settings.width = settings.height = 16;
  const sol::RenderResult single = sol::render_cpu(one, settings);
  settings.samples = 4;
  const sol::RenderResult refined = sol::render_cpu(one, settings);
  const Image early = load_eye(r.dir, 5, 0), last = load_eye(r.dir, 35, 0);
  EXPECT_LE(differing_pixels(early, single, kFloatTolerance), allowed(early));
  EXPECT_LE(differing_pixels(last, refined, kFloatTolerance), allowed(last));
  EXPECT_GT(differing_pixels(last, single, kFloatTolerance), allowed(last));
}

// The render scale follows the display period (--adaptive on): frames of
// lattice-balls at 256 x 256 per eye take lavapipe far longer than the
// runtime's 11.1 ms, so the scale drops, never below --min-scale.
TEST(XrSolxr, TheRenderScaleAdaptsToTheDisplayPeriod) {
  std::string frames;
  for (int k = 0; k < 30; ++k) frames += k == 0 ? "{}" : ", {}";
  const SolxrRun r =
      run_solxr("adaptive", R"({"width": 256, "height": 256, "read_back": false, "frames": [)" + frames + "]}",
                "--scene lattice-balls --adaptive on --min-scale 0.3 --refine 0 --stats");
  expect_clean(r);
  double end = -1, mean = -1;
  const std::size_t at = r.err.find("render scale ");
  ASSERT_NE(at, std::string::npos) << r.err;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "render scale %lf at the end, mean %lf", &end, &mean), 2) << r.err;
  EXPECT_LT(end, 0.9) << r.err;
  EXPECT_GE(end, 0.3) << r.err;
  EXPECT_LT(mean, 1.0) << r.err;
}

// Fixed foveated rendering (--foveation on) against the full render of
// the same frames: the centre level (35 % of the eye around its centre of
// view, here the image's centre) is rendered at full resolution with the
// window of its rectangle and blitted 1:1, so it holds the full render's
// pixels (within the kernel's float tolerance: the sub-window's tangents
// are computed anew); outside it the lower levels differ only at edges of
// the sandwich's pattern, where upsampling blurs them (mean difference
// below 0.02 per channel: measured 0.005 at 256 x 256; a wrong window would
// misplace the whole pattern); and foveation is not a no-op.
TEST(XrSolxr, FoveationKeepsTheCentreAndBlursOnlyEdges) {
  const char* script = R"({"width": 64, "height": 64, "fov": 90, "frames": [{}, {}]})";
  const SolxrRun full = run_solxr("foveation_off", script, "--scene sandwich --refine 0");
  const SolxrRun fovea = run_solxr("foveation_on", script, "--scene sandwich --refine 0 --foveation on");
  expect_clean(full);
  expect_clean(fovea);
  for (int view = 0; view < 2; ++view) {
    const Image a = load_eye(full.dir, 1, view), b = load_eye(fovea.dir, 1, view);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    const int lo = 21, hi = 43;  // the centre level: round(0.35 · 64) = 22 pixels from round(32 - 11)
    int centre_differs = 0, differs = 0;
    double sum = 0;
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        double worst = 0;
        for (int c = 0; c < 3; ++c) {
          const std::size_t k = (static_cast<std::size_t>(y) * 64 + x) * 4 + c;
          const double d = std::abs(a.rgba[k] - b.rgba[k]);
          worst = std::max(worst, d);
          sum += d;
        }
        const bool centre = x >= lo && x < hi && y >= lo && y < hi;
        centre_differs += centre && worst > kFloatTolerance;
        differs += worst > kFloatTolerance;
      }
    }
    EXPECT_LE(centre_differs, (hi - lo) * (hi - lo) / 50) << "view " << view;
    EXPECT_LT(sum / (64.0 * 64.0 * 3.0), 0.02) << "view " << view;
    EXPECT_GT(differs, 0) << "view " << view;
    // The image's edges too: each level is rendered with a ring of a pixel
    // beyond its rectangle, which the linear blit reads at the edge (a
    // blit filters up to the whole source image's edge, not its region's):
    // without it the bottom row and the right eye's right column read
    // texels no dispatch wrote (NaN or black). Every value finite, alpha
    // 1, and the last row and column within the blur of the rest.
    double edge = 0.0;
    for (int k = 0; k < 64; ++k) {
      for (const int at : {(63 * 64 + k) * 4, (k * 64 + 63) * 4}) {
        for (int c = 0; c < 3; ++c) edge += std::abs(a.rgba[static_cast<std::size_t>(at + c)] - b.rgba[static_cast<std::size_t>(at + c)]);
      }
    }
    int not_finite = 0, alpha_not_one = 0;
    for (std::size_t k = 0; k < b.rgba.size(); ++k) {
      not_finite += std::isfinite(b.rgba[k]) ? 0 : 1;
      alpha_not_one += k % 4 == 3 && b.rgba[k] != 1.0f ? 1 : 0;
    }
    EXPECT_EQ(not_finite, 0) << "view " << view;
    EXPECT_EQ(alpha_not_one, 0) << "view " << view;
    EXPECT_LT(edge / (2.0 * 64.0 * 3.0), 0.025) << "view " << view;  // (measured 0.011; 0.04 without the ring)
    std::printf("view %d: mean difference %.4f, on the last row and column %.4f\n", view, sum / (64.0 * 64.0 * 3.0),
                edge / (2.0 * 64.0 * 3.0));
  }
}

// Headsets' eye frusta are off-centre (XrFovf angles, left/right and up/down
// of different sizes): each eye image is the CPU render of that eye with
// the same off-axis window (sol::Frustum), not a centred one.
TEST(XrSolxr, OffCentreFieldsOfViewAreRenderedAsGiven) {
  const SolxrRun r = run_solxr("off_axis", R"({"width": 40, "height": 32, "fov_angles": [-52, 38, -46, 30],
                                             "ipd": 0.1, "frames": [{}]})",
                               "--scene plane");
  expect_clean(r);
  sol::Scene scene = sol::preset_scene("plane");
  const double deg = M_PI / 180.0;
  // The runtime hands the angles over as floats.
  auto tan_of = [&](double a) { return std::tan(static_cast<double>(static_cast<float>(a * deg))); };
  scene.camera.frustum = sol::Frustum{tan_of(-52), tan_of(38), tan_of(-46), tan_of(30)};
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.1);
  const Image l = load_eye(r.dir, 0, 0), rr = load_eye(r.dir, 0, 1);
  EXPECT_LE(differing_pixels(l, cpu_render(scene, eyes.left, 40, 32), kFloatTolerance), allowed(l));
  EXPECT_LE(differing_pixels(rr, cpu_render(scene, eyes.right, 40, 32), kFloatTolerance), allowed(rr));
  // A centred window of the same vertical extent gives another image.
  sol::Scene centred = sol::preset_scene("plane");
  centred.camera.fov = 76.0;
  const sol::StereoEyes centred_eyes = sol::stereo_eyes(centred.camera, 0.1);
  EXPECT_GT(differing_pixels(l, cpu_render(centred, centred_eyes.left, 40, 32), kFloatTolerance), allowed(l));
}

// Both ways into the swapchain image give the CPU render of each eye: the
// device path (the kernel's image blitted on the GPU, the default where the
// formats allow it) and the host path (read back, converted, uploaded), for
// float and 8-bit sRGB swapchains.
TEST(XrSolxr, DeviceAndHostCopiesGiveTheSameEyes) {
  for (const char* copy : {"device", "host"}) {
    for (const char* format : {"rgba32f", "srgb8"}) {
      const std::string name = std::string("copy_") + copy + "_" + format;
      const SolxrRun r = run_solxr(name, std::string(R"({"width": 24, "height": 20, "fov": 55, "ipd": 0.15, "formats": [")") +
                                             format + R"("], "frames": [{}]})",
                                   std::string("--scene sandwich --copy ") + copy);
      expect_clean(r);
      EXPECT_TRUE(contains(r.err, std::string(copy) + " copy into the swapchain")) << r.err;
      sol::Scene scene = sol::preset_scene("sandwich");
      scene.camera.fov = 55;
      const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.15);
      const float tolerance = std::string(format) == "srgb8" ? kSrgbTolerance : kFloatTolerance;
      const Image l = load_eye(r.dir, 0, 0), rr = load_eye(r.dir, 0, 1);
      EXPECT_LE(differing_pixels(l, cpu_render(scene, eyes.left, 24, 20), tolerance), allowed(l)) << name;
      EXPECT_LE(differing_pixels(rr, cpu_render(scene, eyes.right, 24, 20), tolerance), allowed(rr)) << name;
    }
  }
  // The default takes the device path on lavapipe.
  EXPECT_TRUE(contains(run_solxr("copy_default", R"({"frames": [{}]})", "--scene plane").err, "device copy"));
  // The host copy says that it neither adapts the render scale nor refines.
  const SolxrRun host = run_solxr("copy_host_options", R"({"frames": [{}]})", "--scene plane --copy host --adaptive on --refine 4");
  expect_clean(host);
  EXPECT_TRUE(contains(host.err, "no adaptive render scale (--adaptive) and no refinement (--refine)")) << host.err;
}

TEST(XrSolxr, SrgbSwapchainsGetTheSameImage) {
  // (Saved as PNG: the 8-bit sRGB swapchain's bytes as they were, so the tolerance is the same.)
  const SolxrRun r = run_solxr("srgb", R"({"width": 24, "height": 16, "fov": 50, "ipd": 0.1, "formats": ["srgb8"],
                                      "image_format": "png", "frames": [{}]})",
                               "--scene sandwich");
  expect_clean(r);
  sol::Scene scene = sol::preset_scene("sandwich");
  scene.camera.fov = 50;
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.1);
  const Image l = load_eye(r.dir, 0, 0, "png");
  EXPECT_LE(differing_pixels(l, cpu_render(scene, eyes.left, 24, 16), kSrgbTolerance), allowed(l));
  EXPECT_FALSE(fs::exists(r.dir / "frame0_view0.exr"));
}

// The quotient Γ\Sol and the lights come from the scene, as for solrender.
TEST(XrSolxr, QuotientScenesMatchTheCpuRenderToo) {
  const SolxrRun r = run_solxr("quotient", R"({"width": 32, "height": 24, "fov": 70, "ipd": 0.064, "frames": [{}]})",
                               "--scene lattice-balls");
  expect_clean(r);
  sol::Scene scene = sol::preset_scene("lattice-balls");
  ASSERT_NE(scene.quotient(), sol::Quotient::None);
  scene.camera.fov = 70;
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.064);
  const Image l = load_eye(r.dir, 0, 0), rr = load_eye(r.dir, 0, 1);
  EXPECT_LE(differing_pixels(l, cpu_render(scene, eyes.left, 32, 24), kFloatTolerance), allowed(l));
  EXPECT_LE(differing_pixels(rr, cpu_render(scene, eyes.right, 32, 24), kFloatTolerance), allowed(rr));
}

TEST(XrSolxr, ATranslatedTurnedHeadSeesFromTheFlowedEye) {
  // Head 0.4 m right, 0.3 m up, 0.5 m back, turned 30° left; ipd 0.1.
  const SolxrRun r = run_solxr("motion",
                               R"({"width": 32, "height": 32, "fov": 60, "ipd": 0.1,
                              "frames": [{"position": [0.4, 0.3, 0.5], "orientation": [0, 0.25881904510252074, 0, 0.9659258262890683]}]})",
                               "--scene plane");
  expect_clean(r);
  const sol::Scene scene = plane_with_fov(60);
  // Independently of eye_pose.cpp: the runtime puts the left eye at the head
  // position plus the rotated offset (-ipd/2, 0, 0); sol::Observer walks
  // there (flow and transport) and turns by the head's yaw.
  const glm::dquat q = glm::angleAxis(M_PI / 6, glm::dvec3(0, 1, 0));
  const glm::dvec3 t = glm::dvec3(0.4, 0.3, 0.5) + q * glm::dvec3(-0.05, 0, 0);
  sol::Observer eye(scene.camera.position, scene.camera.forward, scene.camera.up);
  eye.move({t.x, t.y, -t.z}, glm::length(t));
  eye.yaw(-M_PI / 6);  // yaw turns right; the head turned left
  sol::Camera camera = scene.camera;
  camera.position = eye.position();
  camera.forward = eye.forward();
  camera.up = eye.up();
  const Image l = load_eye(r.dir, 0, 0);
  EXPECT_LE(differing_pixels(l, cpu_render(scene, camera, 32, 32), kFloatTolerance), allowed(l));
  const sol::RenderResult unmoved = cpu_render(scene, sol::stereo_eyes(scene.camera, 0.1).left, 32, 32);
  EXPECT_GT(differing_pixels(l, unmoved, kFloatTolerance), allowed(l));
}

TEST(XrSolxr, TheLeftStickWalksAlongTheGeodesicAhead) {
  // 90 Hz; --speed 9 walks 0.1 per frame from the second frame on (the first has no elapsed time).
  const SolxrRun r = run_solxr("walk",
                               R"({"width": 32, "height": 32, "fov": 60, "ipd": 0, "controllers": true,
                              "frames": [{"left_stick": [0, 1]}, {"left_stick": [0, 1]}, {"left_stick": [0, 1]},
                                         {"left_stick": [0, 1]}, {"left_stick": [0, 1]}]})",
                               "--scene plane --speed 9");
  expect_clean(r);
  const sol::Scene scene = plane_with_fov(60);
  sol::Observer walker(scene.camera.position, scene.camera.forward, scene.camera.up);
  walker.move({0, 0, 1}, 4 * 9 * 11'111'111e-9);
  sol::Camera camera = scene.camera;
  camera.position = walker.position();
  camera.forward = walker.forward();
  camera.up = walker.up();
  const Image last = load_eye(r.dir, 4, 0);
  EXPECT_LE(differing_pixels(last, cpu_render(scene, camera, 32, 32), kFloatTolerance), allowed(last));
  EXPECT_GT(differing_pixels(last, cpu_render(scene, scene.camera, 32, 32), kFloatTolerance), allowed(last));
}

TEST(XrSolxr, TheRightStickTurns) {
  // --turn-rate 900 turns 10° per 90 Hz frame from the second frame on: 20° right by frame 2.
  const SolxrRun r = run_solxr("turn",
                               R"({"width": 32, "height": 32, "fov": 60, "ipd": 0,
                              "frames": [{"right_stick": [1, 0]}, {"right_stick": [1, 0]}, {"right_stick": [1, 0]}]})",
                               "--scene sandwich --turn-rate 900");
  expect_clean(r);
  sol::Scene scene = sol::preset_scene("sandwich");
  scene.camera.fov = 60;
  sol::Observer turner(scene.camera.position, scene.camera.forward, scene.camera.up);
  turner.yaw(2 * 900 * 11'111'111e-9 * M_PI / 180);
  sol::Camera camera = scene.camera;
  camera.forward = turner.forward();
  camera.up = turner.up();
  const Image last = load_eye(r.dir, 2, 0);
  EXPECT_LE(differing_pixels(last, cpu_render(scene, camera, 32, 32), kFloatTolerance), allowed(last));
  EXPECT_GT(differing_pixels(last, cpu_render(scene, scene.camera, 32, 32), kFloatTolerance), allowed(last));
}

TEST(XrSolxr, WithoutControllersThereIsNoLocomotion) {
  const SolxrRun r = run_solxr("nocontrollers",
                               R"({"width": 16, "height": 16, "ipd": 0, "controllers": false,
                              "frames": [{"left_stick": [0, 1]}, {"left_stick": [0, 1]}, {"left_stick": [0, 1]}]})",
                               "--scene plane --speed 9");
  expect_clean(r);
  EXPECT_TRUE(contains(r.err, "no controllers")) << r.err;
  const sol::Scene scene = plane_with_fov(60);
  const Image last = load_eye(r.dir, 2, 0);
  EXPECT_LE(differing_pixels(last, cpu_render(scene, scene.camera, 16, 16), kFloatTolerance), allowed(last));
}

TEST(XrSolxr, FocusLossAndRuntimeRequestedExitEndCleanly) {
  const SolxrRun r =
      run_solxr("lifecycle",
                R"({"width": 8, "height": 8, "frames": [{}, {"event": "focus_loss"}, {}, {"event": "focus_gain"},
                              {}, {"event": "exit"}, {}, {}, {}, {}]})",
                "--scene plane");
  expect_clean(r);
  // Visible on the way up, after the focus loss and on the way down.
  std::size_t visible = 0;
  for (std::size_t at = r.err.find("visible, not focused"); at != std::string::npos;
       at = r.err.find("visible, not focused", at + 1)) {
    ++visible;
  }
  EXPECT_EQ(visible, 3u) << r.err;
  EXPECT_TRUE(contains(r.err, "session ended")) << r.err;
  // The exit is requested while frame 5 is waited for; every frame, focused
  // or merely visible, was rendered.
  EXPECT_TRUE(contains(r.err, "6 frames ended, 12 images saved")) << r.err;
}

TEST(XrSolxr, LossPendingExitsCleanly) {
  const SolxrRun r =
      run_solxr("loss", R"({"width": 8, "height": 8, "frames": [{}, {"event": "loss_pending"}, {}, {}]})", "");
  expect_clean(r);
  EXPECT_TRUE(contains(r.err, "losing the session")) << r.err;
}

TEST(XrSolxr, FramesOptionAsksTheRuntimeToExit) {
  const SolxrRun r =
      run_solxr("frames", R"({"width": 8, "height": 8, "frames": [{}, {}, {}, {}, {}, {}, {}, {}, {}, {}]})",
                "--frames 3 --stats");
  expect_clean(r);
  // 3, then the one waited for while stopping, which the session is no longer visible for.
  EXPECT_TRUE(contains(r.err, "4 frames ended, 6 images saved")) << r.err;
  // --stats: every rendered stereo frame counted (the three), the intervals'
  // mean and p99 (nearest rank of two: their largest, so at least the mean).
  long n = -1, missed = -1;
  double mean = -1, p99 = -1;
  const std::size_t at = r.err.find("stereo frames: ");
  ASSERT_NE(at, std::string::npos) << r.err;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "stereo frames: %ld, mean %lf ms, p99 %lf ms, missed %ld", &n, &mean, &p99,
                        &missed),
            4)
      << r.err;
  EXPECT_EQ(n, 3);
  EXPECT_GT(mean, 0.0);
  EXPECT_GE(p99, mean);
  EXPECT_GE(missed, 0);
  EXPECT_LE(missed, 3);
  EXPECT_TRUE(contains(r.err, "device work mean")) << r.err;
}

// The test runtime's timing mode ("read_back": false): the views are still
// logged, but no eye image is read back or saved.
TEST(XrSolxr, TimingModeReadsNoImageBack) {
  const SolxrRun r = run_solxr("timing", R"({"width": 8, "height": 8, "read_back": false, "frames": [{}, {}, {}]})", "");
  expect_clean(r);
  EXPECT_TRUE(contains(r.err, "0 images saved")) << r.err;
  EXPECT_TRUE(fs::exists(r.dir / "views.txt"));
  EXPECT_FALSE(fs::exists(r.dir / "frame0_view0.exr"));
}

TEST(XrSolxr, NoRuntimeIsAClearError) {
  const SolxrRun r = run_solxr("noruntime", "{}", "", (fs::path(SOL_XR_TEST_DIR) / "no-such-runtime.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "solxr: no OpenXR runtime available (xrEnumerateInstanceExtensionProperties: XR_ERROR_"))
      << r.err;
}

TEST(XrSolxr, RuntimeWithoutVulkanIsAClearError) {
  const SolxrRun r = run_solxr("novulkan", R"({"mode": "no_vulkan"})", "");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "does not support Vulkan (no XR_KHR_vulkan_enable2)")) << r.err;
  EXPECT_FALSE(contains(r.err, "LEAK")) << r.err;
}

TEST(XrSolxr, NoHeadsetIsAClearError) {
  const SolxrRun r = run_solxr("nohmd", R"({"mode": "no_hmd"})", "");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "finds no headset")) << r.err;
  EXPECT_TRUE(contains(r.err, " 0 objects leaked")) << r.err;
}

TEST(XrSolxr, RecommendedSizesOutOfRangeAreClearErrors) {
  // A runtime that recommends an eye of 0 or 100000 pixels, or one more than
  // solxr renders, is named (it crashed inside the runtime's swapchain
  // creation, aborted, or went on to Vulkan); --width/--height override it.
  for (const char* size : {"0", "100000", "16385"}) {
    const SolxrRun r = run_solxr(std::string("recommended") + size,
                                 std::string(R"({"width": )") + size + R"(, "height": 8, "frames": [{}]})", "--scene plane");
    EXPECT_EQ(r.exit_code, 1) << size << ": " << r.err;
    EXPECT_TRUE(contains(r.err, std::string("the OpenXR runtime recommends an eye width of ") + size)) << r.err;
    EXPECT_TRUE(contains(r.err, "give --width and --height")) << r.err;
    EXPECT_TRUE(contains(r.err, " 0 objects leaked")) << r.err;
  }
  expect_clean(run_solxr("recommended_overridden",
                         R"({"width": 0, "height": 0, "fov_angles": [-30, 30, -25, 25], "frames": [{}]})",
                         "--scene plane --width 8 --height 6"));
}

TEST(XrSolxr, AnEyeBeyondTheHeightsIsAClearError) {
  // The plane scene looks down (-z in Sol) and OpenXR's forward is -z: a head
  // 1000 m forward puts the eye at z = -1000, where nothing can be rendered
  // (it rendered black frames and exited 0).
  const SolxrRun r = run_solxr("eye_too_low", R"({"width": 8, "height": 8, "ipd": 0, "frames": [{"position": [0, 0, -1000]}]})",
                               "--scene plane");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "the head pose at (0, 0, -1000) m (--scale 1) puts the eye where solxr cannot render")) << r.err;
  EXPECT_TRUE(contains(r.err, "height z within [-80, 80]")) << r.err;
  EXPECT_TRUE(contains(r.err, " 0 objects leaked")) << r.err;
}

TEST(XrSolxr, BadOptionsAreClearErrors) {
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--frobnicate", "solxr: unknown option '--frobnicate'"},
      {"--scene tube", "unknown preset 'tube'"},
      {"--scale 0", "--scale must be in [1e-6, 1e6], got 0"},
      {"--scale 1e300", "--scale must be in [1e-6, 1e6], got 1e300"},
      {"--width 0 --height 4", "--width must be in [1, 16384]"},
      {"--width 4", "--width and --height go together"},
      {"--reference floor", "--reference expects local or stage"},
      {"--frames x", "--frames expects an integer"},
      {"--position 1,2", "three comma-separated numbers"},
      {"--speed", "--speed needs a value"},
      {"--copy gpu", "--copy expects auto, device or host, got 'gpu'"},
      {"--render-scale 0", "--render-scale must be in (0, 1]"},
      {"--min-scale 2", "--min-scale must be in (0, 1]"},
      {"--adaptive maybe", "--adaptive expects on or off, got 'maybe'"},
      {"--refine -1", "--refine must be in [0, 4096]"},
  };
  for (const auto& c : cases) {
    const SolxrRun r = run_solxr("badoptions", "{}", c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << c.args << ": " << r.err;
  }
  const SolxrRun help = run_solxr("help", "{}", "--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(contains(help.err, "usage: solxr")) << help.err;
}

}  // namespace
