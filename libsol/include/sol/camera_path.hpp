// Camera paths for films: a start and timed segments that move the
// observer as solview's controls do (sol::Observer: along geodesics, the
// frame parallel-transported; in the quotient teleported back into D).
//
// A path file (JSON, docs/films.md):
//   {"start": {"position": [0, 0, 1.5], "forward": [0, 0, -1], "up": [0, 1, 0], "fov": 90},
//    "segments": [{"walk": "forward", "distance": 2, "duration": 4},
//                 {"turn": "yaw", "degrees": 90, "duration": 2},
//                 {"hold": 1.5}]}
// "start" is optional (the scene's camera), as is each of its keys.
// Walks go "forward", "back", "left", "right", "up" or "down" in the
// observer's frame; turns are "yaw" (forward towards right), "pitch"
// (forward towards up) or "roll" (up towards right), in degrees; a hold
// keeps the camera for its seconds. "look_at": [x, y, z] in the start
// aims the camera at a point (in place of "forward": sol::looking_at); in
// a walk it keeps the camera aimed at the point while it walks (the walk
// goes along the geodesic its direction starts at the walk's start).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/camera.hpp"
#include "sol/lattice.hpp"

namespace sol {

struct PathSegment {
  enum class Kind { Walk, Turn, Hold };
  enum class Axis { Yaw, Pitch, Roll };
  Kind kind = Kind::Hold;
  glm::dvec3 direction{0.0, 0.0, 1.0};  ///< walk: unit, in the observer's (right, up, forward) components
  double distance = 0.0;                ///< walk: Sol units along the geodesic
  Axis axis = Axis::Yaw;                ///< turn
  double angle = 0.0;                   ///< turn: radians
  double duration = 1.0;                ///< seconds, > 0
  /// walk: the point the camera keeps looking at (sol::Observer::face
  /// towards sol::aim's direction at each moment); none: the frame is
  /// parallel-transported.
  std::optional<glm::dvec3> look_at;
};

struct CameraPath {
  /// Overrides of the scene camera's position, forward, up, fov and lens
  /// (aperture, focus distance: sol/lens.hpp).
  std::optional<glm::dvec3> position, forward, up;
  std::optional<double> fov, aperture, focus_distance;
  /// The point the start looks at, in place of `forward` (sol::looking_at).
  /// Where the path gives no focus distance, the lens focuses on the point
  /// the camera last looked at (the start's, then each walk's with a
  /// look_at as it tracks it).
  std::optional<glm::dvec3> look_at;
  std::vector<PathSegment> segments;

  /// Seconds from the start to the end of the last segment.
  double duration() const;
  /// The frames of a film at `fps`: t = k / fps for k in [0, frame_count).
  long frame_count(double fps) const;
  /// The camera at time t, clamped to [0, duration()]: the start (the
  /// scene's camera with this path's overrides) moved by every segment that
  /// ended by t and by the one under way in proportion to its elapsed time,
  /// with sol::Observer (teleported into the domain of `lattice`, the
  /// world's, World::lattice, when there is one). Each segment starts where the last one ended, so the
  /// camera of a frame does not depend on which frames were made before.
  Camera at(double t, const Camera& scene_camera, const std::optional<Lattice>& lattice) const;
};

/// Parses a path; `source` (a file name) prefixes every error, which names
/// the field and its line and column ("path.json: segments[2].duration must
/// be finite and > 0 (line 5, column 40)"). InvalidArgument on bad input.
CameraPath parse_camera_path(std::string_view json, std::string_view source = "<path>");
/// Reads and parses a path file.
CameraPath load_camera_path(const std::string& file);

}  // namespace sol
