// The camera side of the kernel: which pixel an invocation takes, the ray
// of a pixel (docs/conventions.md: perspective with the eye's off-axis
// window, equirectangular, fisheye, omnidirectional stereo columns), and
// how its colour reaches the image (anti-aliasing's running mean, the 8-bit
// output's sRGB encoding).
#ifndef SOL_MARCH_CAMERA_GLSL
#define SOL_MARCH_CAMERA_GLSL

// The pixel of a workgroup's invocation: runs of 8 invocations (lavapipe's
// SIMD group on AVX2: it runs the invocation indices in order, 8 to a
// vector) cover 2 x 4 pixels, four of them side by side make 8 x 4 (a
// 32-lane GPU warp), two such bands the 8 x 8 group. A SIMD group marches
// until its slowest lane is done, and a compact block of pixels holds rays
// of more nearly equal steps than a row of 8 (on lattice-pillars the
// slowest of 8 takes 1.12x the mean steps instead of 1.21x; docs/renderer.md).
ivec2 group_pixel(int index) {
  const int lane = index & 7, run = index >> 3;
  return ivec2((run & 3) * 2 + (lane & 1), (run >> 2) * 4 + (lane >> 1));
}

// What binding 1 receives: the linear colour, or for SOL_OUTPUT_SRGB_UNORM
// the standard sRGB OETF (IEC 61966-2-1) of its display (the exposure's
// scale and the tone curve of params.display, sol/tone.h), what solrender's
// 8-bit files hold (C++ twin: display_byte in common/srgb.hpp;
// Kernel.UnormTargetHoldsTheSrgbEncodedColour holds the two together).
vec4 output_color(vec4 linear) {
#ifdef SOL_OUTPUT_SRGB_UNORM
  const float scale = params.display.x;
  const int tone = int(params.display.y);
  vec3 c = vec3(sol_tone(tone, linear.r * scale), sol_tone(tone, linear.g * scale), sol_tone(tone, linear.b * scale));
  vec3 encoded = mix(kSrgbScale * pow(c, vec3(1.0 / kSrgbGamma)) - kSrgbOffset, kSrgbLinearSlope * c,
                     lessThanEqual(c, vec3(kSrgbLinearLimit)));
  return vec4(encoded, clamp(linear.a, 0.0, 1.0));
#else
  return linear;
#endif
}

// This dispatch's sample of the pixel: its colour, blended into the mean of
// the samples already in the image with the sample's weight (params.pixel_sample.z;
// 1 overwrites). The 8-bit output takes one sample (weight 1): nothing to read.
vec4 accumulate(ivec2 pixel, vec4 color, float weight) {
#ifndef SOL_OUTPUT_SRGB_UNORM
  if (weight < 1.0) color = mix(imageLoad(color_image, pixel), color, weight);
#endif
  return color;
}

// The ray of a point of a pixel of one eye: its unit direction (frame
// components at its start) and where it starts relative to the eye's
// camera (an omnidirectional stereo column's eye, sol::column_eye; else
// there). `sees` is false outside a fisheye's image circle, where there is
// no ray.
struct CameraRay {
  vec3 direction;
  vec3 start;
  bool sees;
};

// The end of the geodesic from the origin with initial velocity v.
vec3 lens_exp(vec3 v) {
  const float n = length(v);
  return n > 0.0 ? sol_exp(v / n, n).position : vec3(0.0);
}

// Depth of field (HAS_LENS; sol::lens_ray, the double reference, and the
// mathematics in sol/lens.hpp): the ray from this dispatch's lens point
// δ = exp(aperture (ξ right + η up)) that meets the pixel ray's focus point
// F = exp(f u), the solution v of exp(v) = δ⁻¹ F near f u by two chord
// steps of Newton's method (the Jacobian at f u by forward differences of
// step 1e-2 f). One loop of six evaluations of exp (δ, F, three
// differences, the second step's residual): one copy of its code. Where the
// steps fail (a conjugate point near F) the ray leaves δ along u, as on the CPU.
void lens_ray(inout CameraRay r, vec3 right, vec3 up) {
  const vec4 lens = params.lens;
  const vec3 offset = lens.z * (lens.x * right + lens.y * up);
  if (lens.z == 0.0 || dot(offset, offset) == 0.0) return;  // the lens's centre: the pixel ray
  const vec3 u = r.direction;
  const float f = lens.w, h = 1e-2 * f;
  vec3 start = vec3(0.0), focus = vec3(0.0), target = vec3(0.0), v = f * u;
  mat3 jacobian = mat3(1.0);
  for (int i = 0; i < 6; ++i) {
    vec3 at = v;
    if (i == 0) at = offset;
    if (i >= 2 && i <= 4) at = f * u + h * vec3(i == 2 ? 1.0 : 0.0, i == 3 ? 1.0 : 0.0, i == 4 ? 1.0 : 0.0);
    const vec3 p = lens_exp(at);
    if (i == 0) start = p;
    if (i == 1) {
      focus = p;
      target = sol_translate(vec3(-exp(-start.z) * start.x, -exp(start.z) * start.y, -start.z), focus);
    }
    if (i == 2) jacobian[0] = (p - focus) / h;
    if (i == 3) jacobian[1] = (p - focus) / h;
    if (i == 4) {
      jacobian[2] = (p - focus) / h;
      v = f * u + inverse(jacobian) * (target - focus);
    }
    if (i == 5) v += inverse(jacobian) * (target - p);
  }
  r.start = start;
  const bool focused = !any(isnan(v)) && !any(isinf(v)) && length(v - f * u) <= 0.5 * f + 2.0 * lens.z;
  r.direction = focused ? normalize(v) : u;
}

// Pixel `local` of eye `eye` (each width x height) at `sample_at.xy` in the
// pixel (sol::camera_ray).
CameraRay camera_ray(int eye, ivec2 local, int width, int height, vec4 sample_at) {
  CameraRay r;
  r.start = vec3(0.0);
  r.sees = true;
  const vec4 eye_right = params.eyes[eye].right, eye_up = params.eyes[eye].up, eye_forward = params.eyes[eye].forward;
  // The camera convention of docs/conventions.md (or the eye's off-axis window), per eye.
  const vec4 window = params.eyes[eye].window;
  const float sx = window.x + (window.y - window.x) * (float(local.x) + sample_at.x) / float(width);
  const float sy = window.z + (window.w - window.z) * (float(local.y) + sample_at.y) / float(height);
  r.direction = normalize(sx * eye_right.xyz + sy * eye_up.xyz + eye_forward.xyz);
  // The other projections (sol::camera_ray): equirectangular and fisheye.
  const vec4 projection = params.eyes[eye].projection;
  const vec2 at = vec2(float(local.x) + sample_at.x, float(local.y) + sample_at.y);
  if (HAS_PROJECTIONS && projection.x == float(kProjectionEquirectangular)) {
    const float longitude = (at.x / float(width) - 0.5) * 6.28318530717958648;
    const float latitude = (0.5 - at.y / float(height)) * 3.14159265358979324;
    r.direction = normalize(cos(latitude) * sin(longitude) * eye_right.xyz + sin(latitude) * eye_up.xyz +
                            cos(latitude) * cos(longitude) * eye_forward.xyz);
  } else if (HAS_PROJECTIONS && projection.x == float(kProjectionFisheye)) {
    const vec2 p = vec2(at.x - 0.5 * float(width), 0.5 * float(height) - at.y) / (0.5 * float(min(width, height)));
    const float radius = length(p);
    if (radius > 1.0) {  // outside the image circle: no ray
      r.sees = false;
      return r;
    }
    const float theta = radius * projection.y;
    r.direction = radius > 0.0
                      ? normalize(sin(theta) * (p.x / radius * eye_right.xyz + p.y / radius * eye_up.xyz) +
                                  cos(theta) * eye_forward.xyz)
                      : eye_forward.xyz;
  }
  if (HAS_LENS) lens_ray(r, eye_right.xyz, eye_up.xyz);
  // An omnidirectional stereo eye's column has its own eye: the start
  // `offset`, the direction transported there.
  if (HAS_ODS) {
    const Column column = columns[eye * width + local.x];
    r.start = column.offset.xyz;
    r.direction = normalize(mat3(column.transport[0].xyz, column.transport[1].xyz, column.transport[2].xyz) * r.direction);
  }
  return r;
}

#endif  // SOL_MARCH_CAMERA_GLSL
