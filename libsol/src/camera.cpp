#include "sol/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "sol/error.hpp"
#include "sol/geodesic.hpp"

namespace sol {
namespace detail {

// The checks behind validate(Camera), also run on the camera of a scene file.
void check_camera(const Camera& c) {
  check_position(c.position, "camera.position");
  check_direction(c.forward, "camera.forward");
  check_direction(c.up, "camera.up");
  if (glm::length(glm::cross(glm::normalize(c.forward), glm::normalize(c.up))) < 1e-9) {
    field_error("camera.forward", "camera.forward and camera.up must not be parallel");
  }
  if (!(c.fov > 0.0 && c.fov < 180.0)) field_error("camera.fov", "camera.fov must be in (0, 180) degrees");
  if (c.projection == Projection::Fisheye && !(c.fisheye_fov > 0.0 && c.fisheye_fov <= 360.0)) {
    field_error("camera.fisheye_fov", "camera.fisheye_fov must be in (0, 360] degrees");
  }
  if (!(std::abs(c.eye_offset) <= 10.0)) {
    field_error("camera.eye_offset", "camera.eye_offset must be finite and within [-10, 10]");
  }
  if (c.eye_offset != 0.0 && c.projection != Projection::Equirectangular) {
    field_error("camera.eye_offset", "camera.eye_offset (omnidirectional stereo) is for the equirectangular projection only");
  }
  if (!(c.aperture >= 0.0 && c.aperture <= 1.0)) field_error("camera.aperture", "camera.aperture must be in [0, 1]");
  if (!(c.focus_distance > 0.0 && c.focus_distance <= 100.0)) {
    field_error("camera.focus_distance", "camera.focus_distance must be in (0, 100]");
  }
  if (c.aperture > 0.0 && c.projection == Projection::Equirectangular) {
    field_error("camera.aperture", "camera.aperture (depth of field) is for the perspective and fisheye projections only");
  }
  if (c.frustum && c.projection != Projection::Perspective) {
    field_error("camera.frustum", "camera.frustum is for the perspective projection only");
  }
  if (c.frustum) {
    // Tangents up to 1e3: edges up to 89.94° from forward.
    const Frustum& f = *c.frustum;
    for (const double v : {f.left, f.right, f.down, f.up}) {
      if (!(std::abs(v) <= 1e3)) {
        field_error("camera.frustum", "camera.frustum tangents must be finite and within [-1000, 1000]");
      }
    }
    if (!(f.left < f.right) || !(f.down < f.up)) {
      field_error("camera.frustum", "camera.frustum must have left < right and down < up");
    }
  }
}

}  // namespace detail

void validate(const Camera& camera) {
  detail::validate_as("sol::validate(Camera)", [&] { detail::check_camera(camera); });
}

namespace {

double tan_half_fov(const Camera& camera) { return std::tan(camera.fov * 0.5 * std::numbers::pi / 180.0); }

}  // namespace

CameraBasis camera_basis(const Camera& camera) {
  const glm::dvec3 forward = glm::normalize(camera.forward);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  return {right, glm::cross(right, forward), forward, tan_half_fov(camera)};
}

glm::dvec4 image_window(const Camera& camera, int width, int height) {
  if (camera.frustum) return {camera.frustum->left, camera.frustum->right, camera.frustum->up, camera.frustum->down};
  const double t = tan_half_fov(camera);
  const double aspect = static_cast<double>(width) / height;
  return {-t * aspect, t * aspect, t, -t};
}

glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height) {
  return camera_ray(camera, i, j, width, height, {0.5, 0.5});
}

namespace {

// The fisheye's point p of a pixel point: centred, in units of the image circle's radius.
glm::dvec2 fisheye_point(int i, int j, int width, int height, const glm::dvec2& offset) {
  const double radius = 0.5 * std::min(width, height);
  return {(i + offset.x - 0.5 * width) / radius, (0.5 * height - (j + offset.y)) / radius};
}

}  // namespace

bool camera_sees(const Camera& camera, int i, int j, int width, int height, const glm::dvec2& offset) {
  if (camera.projection != Projection::Fisheye) return true;
  return glm::length(fisheye_point(i, j, width, height, offset)) <= 1.0;
}

namespace {

// The longitude of a point of column i (offset x in [0, 1) across it).
double longitude_of(double x, int width) { return (x / width - 0.5) * 2.0 * std::numbers::pi; }

}  // namespace

ColumnEye column_eye(const Camera& camera, int i, int width) {
  if (camera.projection != Projection::Equirectangular || camera.eye_offset == 0.0) return {};
  const CameraBasis b = camera_basis(camera);
  const double longitude = longitude_of(i + 0.5, width);
  const glm::dvec3 right = std::cos(longitude) * b.right - std::sin(longitude) * b.forward;
  // From the origin: left translations carry the flow and its transport to any position.
  const FlowTransport ft = flow_with_transport({glm::dvec3(0.0), right}, camera.eye_offset, FlowOptions{});
  return {ft.state.position, ft.transport};
}

glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height, const glm::dvec2& offset) {
  const CameraBasis b = camera_basis(camera);
  if (camera.projection == Projection::Equirectangular) {
    const double longitude = longitude_of(i + offset.x, width);
    const double latitude = (0.5 - (j + offset.y) / height) * std::numbers::pi;
    const glm::dvec3 mono = std::cos(latitude) * std::sin(longitude) * b.right + std::sin(latitude) * b.up +
                            std::cos(latitude) * std::cos(longitude) * b.forward;
    if (camera.eye_offset == 0.0) return glm::normalize(mono);
    return glm::normalize(column_eye(camera, i, width).transport * mono);
  }
  if (camera.projection == Projection::Fisheye) {
    const glm::dvec2 p = fisheye_point(i, j, width, height, offset);
    const double r = glm::length(p);
    if (r == 0.0) return b.forward;
    const double theta = r * camera.fisheye_fov * 0.5 * std::numbers::pi / 180.0;
    return glm::normalize(std::sin(theta) * (p.x / r * b.right + p.y / r * b.up) + std::cos(theta) * b.forward);
  }
  const glm::dvec4 window = image_window(camera, width, height);
  const double sx = window.x + (window.y - window.x) * (i + offset.x) / width;
  const double sy = window.z + (window.w - window.z) * (j + offset.y) / height;
  return glm::normalize(sx * b.right + sy * b.up + b.forward);
}

glm::dvec2 pixel_sample(int k) {
  if (k < 0) throw InvalidArgument("sol::pixel_sample: k must be >= 0, got " + std::to_string(k));
  constexpr double g = 1.32471795724474602596;  // the plastic number: g³ = g + 1
  // k/g and k/g² reduced modulo 1 in long double: k up to 2^31 keeps 1e-9 of the fraction.
  const long double x = 0.5L + static_cast<long double>(k) / g, y = 0.5L + static_cast<long double>(k) / (static_cast<long double>(g) * g);
  return {static_cast<double>(x - std::floor(x)), static_cast<double>(y - std::floor(y))};
}

StereoEyes stereo_eyes(const Camera& camera, double ipd) {
  if (!std::isfinite(ipd) || ipd < 0.0) {
    throw InvalidArgument("sol::stereo_eyes: ipd must be finite and >= 0, got " + std::to_string(ipd));
  }
  if (camera.projection == Projection::Equirectangular) {
    // Omnidirectional stereo: each column flows along its own right vector.
    Camera left = camera, right = camera;
    left.eye_offset = -0.5 * ipd;
    right.eye_offset = 0.5 * ipd;
    return {left, right};
  }
  const CameraBasis basis = camera_basis(camera);
  auto eye = [&](double t) {
    // Flow along `right` by t; the frame vectors follow by parallel transport.
    const FlowTransport ft = flow_with_transport({camera.position, basis.right}, t, FlowOptions{});
    Camera c = camera;
    c.position = ft.state.position;
    c.forward = ft.transport * basis.forward;
    c.up = ft.transport * basis.up;
    return c;
  };
  return {eye(-0.5 * ipd), eye(0.5 * ipd)};
}

}  // namespace sol
