#include "eye_pose.hpp"

#include <cmath>
#include <sol/geodesic.hpp>

namespace sol::xr {

Camera eye_camera(const Observer& base, const ViewPose& pose, double scale, const Camera& base_camera) {
  // Observer-local components (right, up, forward) of an OpenXR vector.
  auto local = [](const glm::dvec3& v) { return glm::dvec3(v.x, v.y, -v.z); };
  glm::dvec3 position = base.position();
  glm::dmat3 frame = base.frame();  // columns right, up, forward (frame components)
  const glm::dvec3 d = frame * local(pose.position) * scale;
  const double length = glm::length(d);
  if (length > 0.0) {
    const FlowTransport ft = flow_with_transport({position, d / length}, length, FlowOptions{});
    position = ft.state.position;
    frame = ft.transport * frame;
  }
  // The eye looks along -z and has +y up in its own pose; q turns them into
  // reference-space axes, which the transported frame maps to Sol.
  const glm::dquat q = glm::normalize(pose.orientation);
  Camera eye = base_camera;
  eye.position = position;
  eye.forward = frame * local(q * glm::dvec3(0.0, 0.0, -1.0));
  eye.up = frame * local(q * glm::dvec3(0.0, 1.0, 0.0));
  return eye;
}

}  // namespace sol::xr
