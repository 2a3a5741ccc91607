// From an OpenXR view pose to a Sol eye (solxr's head tracking).
//
// The base observer stands in Sol with a position and a frame (right, up,
// forward). An XR view pose in the reference space is a translation t
// (OpenXR axes: +x right, +y up, -z forward; metres) and an orientation q.
// The eye is placed by the exponential map at the base observer: t, scaled
// to Sol units and written in the base frame as the tangent vector
// d = s (t.x right + t.y up - t.z forward), is followed along the Sol geodesic
// from the base for arc length |d|, and the base frame is parallel-transported
// along it; the eye's frame is then that transported frame turned by q.
//
// Why this one: it uses nothing but the metric and the base frame (no
// coordinates, so it commutes with every isometry, left-translations
// included); the eye is at Sol distance exactly |d| from the base, along the
// direction the head moved (the exponential map is a radial isometry), so
// small head motions look Euclidean to first order; and eyes at (∓ipd/2, 0, 0)
// with q = identity are exactly sol::stereo_eyes (docs/conventions.md), so the
// runtime's eye separation is the stereo baseline.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <sol/observer.hpp>
#include <sol/scene.hpp>

namespace sol::xr {

struct ViewPose {
  glm::dvec3 position{0.0};                    ///< metres, reference space (OpenXR axes)
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< unit quaternion (w, x, y, z)
};

/// The eye camera (position, forward, up; fov left as in `base_camera`) for
/// `pose` seen from the observer `base`; `scale` Sol units per metre (> 0).
Camera eye_camera(const Observer& base, const ViewPose& pose, double scale, const Camera& base_camera);

}  // namespace sol::xr
