// The kernel's passes (sol/vk/march_interface.h, docs/renderer.md "Deferred
// passes"): the march pass takes an invocation's pixel, marches its camera
// ray and writes its colour and AOVs (or lists the ray for the resume pass,
// the hit for the shade pass); the resume pass goes on with a listed ray;
// the shade pass shades a listed hit.
#ifndef SOL_MARCH_PASSES_GLSL
#define SOL_MARCH_PASSES_GLSL

// This invocation's marches that ran out of steps (g_out_of_steps) into the
// frame's count and the pixel's AOV (the hit AOV's w): written with the
// AOVs (`written`: the sample that writes them, its count in `hit_aov`),
// or added to what an earlier sample or pass wrote.
void report_out_of_steps(ivec2 pixel, bool written) {
  if (g_out_of_steps == 0) return;
  atomicAdd(stats.out_of_steps.x, uint(g_out_of_steps));
  if (WRITE_AOVS && !written) imageStore(aov_hit, pixel, imageLoad(aov_hit, pixel) + vec4(0.0, 0.0, 0.0, float(g_out_of_steps)));
}

// What the sample writes besides the colour (pixel_sample.w: kSampleColourOnly
// ... kSampleJoinsGuides; a presenter's probe binds no images for the guides
// and never asks for them).
int sample_writes() { return int(params.pixel_sample.w + 0.5); }
bool writes_aovs() { return WRITE_AOVS && (sample_writes() == kSampleAovs || sample_writes() == kSampleAovsAndGuides); }
bool writes_guides() { return WRITE_AOVS && sample_writes() >= kSampleAovsAndGuides; }

// What a camera ray's hit (its surface `f`, at arc length t) emits towards the eye.
vec3 emitted_towards_eye(Surface f, float t) {
  return HAS_EMISSION ? scene_objects[f.object].material.rgb * fog_transmittance(t) : vec3(0.0);
}

// The square of the luminance of a sample's light, its colour less what
// its first hit emits: joined to the pixel's mean, the denoiser's light
// moment (sol/denoise.h), in the emission guide's w.
float light_square(vec3 color, vec3 emitted) {
  const float l = sol_denoise_luminance(color - emitted);
  return l * l;
}

// A camera ray's hit's albedo and what it emits towards the eye (over the
// fog of `t`), joined to the pixel's means with the sample's weight (1
// overwrites), and with the sample's colour (`shaded`; else the shade pass
// joins it: join_light_square) its light's square; its normal with sample
// 0 (the centre's). `f.object` < 0: a miss, 0.
void write_guides_of(ivec2 pixel, Surface f, float t, vec3 color, bool shaded) {
  const bool hit = f.object >= 0;
  vec4 a = vec4(0.0), e = vec4(0.0);
  if (hit) {
    a.rgb = albedo(f.object, f.uv);
    e.rgb = emitted_towards_eye(f, t);
  }
  e.w = shaded ? light_square(color, e.rgb) : 0.0;
  const float weight = params.pixel_sample.z;
  if (weight < 1.0) {
    a = mix(imageLoad(aov_albedo, pixel), a, weight);
    const vec4 before = imageLoad(aov_emission, pixel);
    e = mix(before, e, weight);
    if (!shaded) e.w = before.w;
  }
  imageStore(aov_albedo, pixel, a);
  imageStore(aov_emission, pixel, e);
  if (sample_writes() == kSampleAovsAndGuides) imageStore(aov_normal, pixel, hit ? vec4(f.n, 0.0) : vec4(0.0));
}

// The shade pass's colour of a deferred hit: its light's square joined to
// the pixel's light moment, as write_guides_of joins the others'.
void join_light_square(ivec2 pixel, Surface f, float t, vec3 color) {
  vec4 e = imageLoad(aov_emission, pixel);
  const float square = light_square(color, emitted_towards_eye(f, t));
  const float weight = params.pixel_sample.z;
  e.w = weight < 1.0 ? mix(e.w, square, weight) : square;
  imageStore(aov_emission, pixel, e);
}

// The AOVs of a camera ray's hit (`hit`, its surface `f`; `f.object` < 0
// a miss, all 0) where the sample writes them, and the guides where it
// joins them (with its colour where `shaded`).
void write_aovs_of(ivec2 pixel, vec4 hit_aov, vec4 point_aov, Surface f, vec3 color, bool shaded) {
  if (writes_aovs()) {
    imageStore(aov_hit, pixel, hit_aov);
    imageStore(aov_point, pixel, point_aov);
  }
  if (writes_guides()) write_guides_of(pixel, f, hit_aov.y, color, shaded);
}

// From the eye (PATH_FROM_EYE, march/paths.glsl; DIRECT_FROM_EYE,
// march/shading.glsl): the pixel's path or radiance, its camera ray its
// first segment, and its colour and AOVs written.
void from_eye_pass(ivec2 pixel, int eye, uint index, vec3 origin, vec3 direction, bool write_aovs) {
  MarchHit h = march_hit_none(kMarchFromStart), first;
  h.q = origin;
  h.u = direction;
  Surface f, first_f;
  f.object = -1;
  vec4 color;
  if (PATH_FROM_EYE) {
    color = path_radiance(h, f, eye, index, true, first, first_f);
  } else {
    color = radiance(h, f, eye, index, first, first_f);
  }
  imageStore(color_image, pixel, output_color(accumulate(pixel, color, params.pixel_sample.z)));
  if (write_aovs) {
    vec4 hit_aov = vec4(0.0, 0.0, float(first.steps), float(g_out_of_steps)), point_aov = vec4(0.0);
    if (first.k >= 0) {
      hit_aov.xy = vec2(float(first_f.object + 1), first.t);
      point_aov = vec4(first_f.world, 0.0);
    } else {
      first_f.object = -1;
    }
    write_aovs_of(pixel, hit_aov, point_aov, first_f, color.rgb, true);
  }
  report_out_of_steps(pixel, writes_aovs());
}

// The march and resume passes: a pixel's camera ray, marched (the resume
// pass goes on with a ray the march pass listed), and its colour and AOVs
// written, or its hit listed for the shade pass.
void march_pass() {
  // This dispatch's tile of the image (the whole image unless rendered in tiles).
  const ivec4 tile = params.tile;
  // The resume pass: the ray of a record of the march pass (defer_exact),
  // which goes on from where that pass left it.
  uvec4 resumed = uvec4(0u);
  ivec2 pixel;
  if (PASS == kPassResume) {
    const int slot = queue_slot();
    if (slot >= queue.resume.w) return;
    resumed = queue_records[kQueueResumeRecord * slot];
    pixel = unpack_pixel(resumed.x);
  } else {
    const ivec2 invocation = ivec2(gl_WorkGroupID.xy) * kGroupSize + group_pixel(int(gl_LocalInvocationIndex));
    if (any(greaterThanEqual(invocation, tile.zw))) return;
    pixel = tile.xy + invocation;
  }
  const int width = params.counts.y, height = params.counts.z;
  if (pixel.x >= width * params.counts.w || pixel.y >= height) return;
  const int eye = pixel.x >= width ? 1 : 0;
  const ivec2 local = ivec2(pixel.x - eye * width, pixel.y);
  // The point of the pixel this dispatch samples (the centre without anti-aliasing).
  const vec4 sample_at = params.pixel_sample;
  const bool write_aovs = WRITE_AOVS && sample_writes() != kSampleColourOnly;  // (the AOVs, or the guides alone: write_aovs_of)
  const CameraRay ray = camera_ray(eye, local, width, height, sample_at);
  if (!ray.sees) {
    imageStore(color_image, pixel, output_color(accumulate(pixel, vec4(0.0, 0.0, 0.0, 1.0), sample_at.z)));
    if (write_aovs) {
      Surface none;
      none.object = -1;
      write_aovs_of(pixel, vec4(0.0), vec4(0.0), none, vec3(0.0), true);
    }
    return;
  }
  // Where the march starts: in Sol relative to the eye (its camera, an ODS
  // column's eye or the lens point); in the quotient the eye's point of D
  // (from double), or the column's eye or lens point teleported into D.
  vec3 origin = ray.start;
  vec3 direction = ray.direction;
  if (QUOTIENT) {
    origin = params.eyes[eye].camera.xyz;
    if (HAS_ODS || HAS_LENS) {
      origin = sol_translate(origin, ray.start);
      float turn = 1.0;
      if (!in_domain(origin)) origin = teleport(origin, false, turn);
      direction.xy *= turn;
    }
  } else {
    load_objects(eye);
  }
  if (PATH_FROM_EYE || DIRECT_FROM_EYE) {
    from_eye_pass(pixel, eye, uint(local.y * width + local.x), origin, direction, write_aovs);
    return;
  }
  const MarchHit h = march(origin, direction, params.limits.x,
                           MarchResume(uintBitsToFloat(resumed.y), resumed.z, int(resumed.w), 0u, -1, 0.0), kMarchCamera);
  if (h.deferred) {  // the rest of this ray in the resume pass
    defer_exact(pixel, h.resume.t, h.resume.passing, h.resume.step);
    return;
  }
  vec4 color = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 hit_aov = vec4(0.0, 0.0, float(h.steps), 0.0);
  vec4 point_aov = vec4(0.0);
  Surface hit_f;
  hit_f.object = -1;
  if (h.k >= 0) {
    const Surface f = surface_at(h);
    hit_f = f;
    if (DEFER_SHADING) {
      defer_shading(pixel, h.q, h.t, f.n, f.object, f.uv, h.u);
    } else if (PATH_TRACING) {
      MarchHit first;
      Surface first_f;
      color = path_radiance(h, f, eye, uint(local.y * width + local.x), false, first, first_f);
    } else {
      MarchHit first;
      Surface first_f;
      color = radiance(h, f, eye, uint(local.y * width + local.x), first, first_f);  // (without mirrors and emission: shade_hit's colour, to the bit)
    }
    hit_aov.x = float(f.object + 1);
    hit_aov.y = h.t;
    point_aov = vec4(f.world, 0.0);
  }
  // (A hit's colour comes from the shade pass.)
  if (!DEFER_SHADING || h.k < 0) imageStore(color_image, pixel, output_color(accumulate(pixel, color, sample_at.z)));
  if (write_aovs) {
    hit_aov.w = float(g_out_of_steps);
    write_aovs_of(pixel, hit_aov, point_aov, hit_f, color.rgb, !DEFER_SHADING || h.k < 0);
  }
  report_out_of_steps(pixel, writes_aovs());
}

// The shade pass: the hits the march pass listed (defer_shading), shaded
// into their pixels as the march pass would have: by radiance (its
// reflected rays marched in this pass alone), with paths by path_radiance
// from the hit (its marches too).
void shade_pass() {
  const int slot = queue_slot();
  if (slot >= queue.shade.w) return;
  const int at = kQueueResumeRecord * queue_capacity() + kQueueShadeRecord * slot;
  const uvec4 a = queue_records[at], b = queue_records[at + 1], c = queue_records[at + 2];
  const ivec2 pixel = unpack_pixel(b.z);
  const int width = params.counts.y;
  const int eye = pixel.x >= width ? 1 : 0;
  MarchHit h = march_hit_none(kMarchFromStart);
  h.q = uintBitsToFloat(a.xyz);
  h.t = uintBitsToFloat(a.w);
  h.u = octahedral_decode(uintBitsToFloat(c.zw));
  Surface f;
  f.object = int(b.w);
  f.n = octahedral_decode(uintBitsToFloat(b.xy));
  f.uv = uintBitsToFloat(c.xy);
  if (!QUOTIENT && (HAS_SHADOWS || HAS_MIRRORS || PATH_TRACING)) load_objects(eye);  // (this pass's marches)
  vec4 color;
  const ivec2 local = ivec2(pixel.x - eye * width, pixel.y);
  if (PATH_TRACING) {
    MarchHit first;
    Surface first_f;
    color = path_radiance(h, f, eye, uint(local.y * width + local.x), false, first, first_f);
  } else {
    MarchHit first;
    Surface first_f;
    color = radiance(h, f, eye, uint(local.y * width + local.x), first, first_f);  // (its reflected rays marched here)
  }
  imageStore(color_image, pixel, output_color(accumulate(pixel, color, params.pixel_sample.z)));
  if (writes_guides()) join_light_square(pixel, f, h.t, color.rgb);
  report_out_of_steps(pixel, false);  // (its shadow rays' and paths')
}

#endif  // SOL_MARCH_PASSES_GLSL
