// The camera model: where an eye is, how its pixels map to the directions of
// their rays, and the two eyes of a stereo pair (docs/conventions.md).
//
// A camera sits at `position` (Sol coordinates) and looks along `forward`
// with `up`, both given by their frame components at the position:
// right = normalize(forward × up), up' = right × forward. The centre of
// pixel (i, j) (row 0 at the top) of a W × H image looks along
// normalize(s_x right + s_y up' + forward), with s_x, s_y spanning the
// image's window (image_window): the centred window of the vertical field
// of view, or an off-axis Frustum (a headset eye's).
#pragma once

#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sol {

/// An off-axis view window (a headset eye's): the tangents of the angles
/// from `forward` to the image's left, right, bottom and top edges, measured
/// towards right and up (so left < right, down < up; OpenXR's XrFovf gives
/// tan(angleLeft), tan(angleRight), tan(angleDown), tan(angleUp)).
struct Frustum {
  double left = -1.0, right = 1.0, down = -1.0, up = 1.0;
};

/// How pixels map to directions (docs/conventions.md "Projections").
enum class Projection {
  Perspective,      ///< the pinhole camera of `fov` (or a frustum)
  Equirectangular,  ///< 360° × 180°: column → longitude, row → latitude (width = 2 × height)
  Fisheye,          ///< equidistant: the angle from forward grows linearly to fisheye_fov/2 at the image circle's rim
};

struct Camera {
  glm::dvec3 position{0.0, 0.0, 0.0};
  glm::dvec3 forward{1.0, 0.0, 0.0};  ///< frame components at position
  glm::dvec3 up{0.0, 0.0, 1.0};       ///< frame components; not parallel to forward
  double fov = 60.0;                  ///< vertical field of view, degrees, in (0, 180)
  /// When set, the image spans this window instead of the centred one of
  /// `fov` and the image's aspect ratio (sol::image_window).
  std::optional<Frustum> frustum;
  Projection projection = Projection::Perspective;
  /// Fisheye: the angle across the image circle (the largest circle centred
  /// in the image), degrees in (0, 360]; 180 is a dome.
  double fisheye_fov = 180.0;
  /// Equirectangular only: one eye of an omnidirectional stereo (ODS) pair
  /// (sol::stereo_eyes makes them). Each column's rays start at the geodesic
  /// flow of `position` by this signed arc length along that column's own
  /// right vector (-ipd/2 for the left eye, +ipd/2 for the right), their
  /// directions parallel-transported along that flow (sol::column_eye).
  /// 0: a mono panorama, every ray from `position`.
  double eye_offset = 0.0;
  /// Depth of field (sol/lens.hpp): the radius of a thin lens in the plane
  /// of right and up, an arc length in [0, 1]; 0, the default, is the
  /// pinhole camera. Perspective and fisheye cameras only.
  double aperture = 0.0;
  /// The arc length along each pixel's geodesic from the eye at which the
  /// lens focuses, in (0, 100].
  double focus_distance = 2.0;
};

/// Checks the camera (finite position within 1e15 of the origin, non-zero
/// and non-parallel forward and up, fov in (0, 180), a frustum's order and
/// range); throws InvalidArgument naming the field ("camera.fov ...").
void validate(const Camera& camera);

/// The camera's orthonormal basis (frame components):
/// right = normalize(forward × up), up' = right × forward.
struct CameraBasis {
  glm::dvec3 right, up, forward;
  double tan_half_fov;  ///< tan(fov / 2)
};
CameraBasis camera_basis(const Camera& camera);

/// The image's window on the plane one unit along forward, as
/// (s_x at the left edge, s_x at the right edge, s_y at the top edge, s_y at
/// the bottom edge): the centre of pixel (i, j) of a width × height image
/// looks along s_x·right + s_y·up + forward, s_x and s_y interpolated
/// linearly at (i + 0.5)/width and (j + 0.5)/height. Without a frustum:
/// (-t·width/height, t·width/height, t, -t), t = tan(fov/2); with one:
/// (left, right, up, down).
glm::dvec4 image_window(const Camera& camera, int width, int height);

/// The ray through the centre of pixel (i, j) (row 0 at the top) of a
/// width × height image: unit direction in frame components at the camera.
/// Perspective: as image_window says. Equirectangular: longitude
/// λ = (u − 1/2)·2π, latitude φ = (1/2 − v)·π with u = (i + ½)/width,
/// v = (j + ½)/height; direction cos φ sin λ right + sin φ up + cos φ cos λ
/// forward (column 0 and the last column are neighbours across λ = ±π).
/// Fisheye: p = ((i + ½) − width/2, height/2 − (j + ½)) / (min(width,
/// height)/2), θ = |p|·fisheye_fov/2, direction sin θ (p/|p|)·(right, up) +
/// cos θ forward; outside the image circle (|p| > 1) there is no ray
/// (camera_sees is false; renderers show black there). An ODS eye's
/// directions are those at its column's eye (sol::column_eye).
glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height);
/// The ray through the point `offset` of pixel (i, j), offset in [0, 1)²
/// from the pixel's top-left corner ((0.5, 0.5): the centre, as above).
glm::dvec3 camera_ray(const Camera& camera, int i, int j, int width, int height, const glm::dvec2& offset);

/// The k-th sample point inside a pixel (k >= 0) for anti-aliasing, as an
/// offset in [0, 1)² from its top-left corner: the R2 sequence (Roberts
/// 2018), (frac(1/2 + k/g), frac(1/2 + k/g²)) with g the plastic number
/// (g³ = g + 1), a low-discrepancy sequence whose every prefix is spread
/// evenly over the pixel (so a progressive render can stop after any
/// sample). Sample 0 is the centre: one sample is the image without
/// anti-aliasing. Every pixel takes the same point for sample k.
glm::dvec2 pixel_sample(int k);

/// Whether the point `offset` of pixel (i, j) has a ray: false only outside a fisheye's image circle.
bool camera_sees(const Camera& camera, int i, int j, int width, int height, const glm::dvec2& offset = {0.5, 0.5});

/// Where the rays of column i of a width-wide image start, relative to the
/// camera. For an ODS eye (equirectangular with eye_offset ≠ 0): the camera
/// turned to face the column centre's longitude λ_i = ((i + ½)/width − ½)·2π
/// has the right vector r_i = cos λ_i right − sin λ_i forward; the column's
/// eye is the geodesic flow from the camera along r_i by eye_offset, i.e.
/// the eye of sol::stereo_eyes of that turned camera. `offset` is that eye
/// in the camera's own coordinates (the eye is multiply(position, offset):
/// Sol's left translations carry geodesics and the frame, so offset and
/// transport do not depend on the position) and `transport` maps frame
/// components at the camera to those at the eye (parallel transport along
/// the flow). Every sample of the column shares them; its direction is
/// transport · (the mono panorama's direction of that sample). For every
/// other camera: offset 0 and the identity.
struct ColumnEye {
  glm::dvec3 offset{0.0};
  glm::dmat3 transport{1.0};
};
ColumnEye column_eye(const Camera& camera, int i, int width);

/// The two eyes of a stereo pair, with the same field of view and
/// projection. Perspective and fisheye: at the geodesic flow of the camera
/// by ∓ipd/2 along its right vector, their frames (forward, up) parallel-
/// transported along that flow. Equirectangular: omnidirectional stereo,
/// the camera twice with eye_offset = ∓ipd/2 (each column its own eye,
/// sol::column_eye). ipd must be finite and >= 0 (InvalidArgument otherwise).
struct StereoEyes {
  Camera left, right;
};
StereoEyes stereo_eyes(const Camera& camera, double ipd);

}  // namespace sol
