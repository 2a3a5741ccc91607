// Shading: the light a hit receives (sol::lights_at: directional and point
// lights, exact point lights along each geodesic to the light and, in the
// quotient, to each of its images, with their falloff and shadows), the
// surface's colour and pattern, and fog.
#ifndef SOL_MARCH_SHADING_GLSL
#define SOL_MARCH_SHADING_GLSL

// The light the lights bring to a point q with unit normal n (frame
// components), before the surface's colour and the ambient (light_received
// in libsol/src/render.cpp), gathered a shadow ray and a connection solve
// at a time, so that the caller's one march serves the shadow rays and its
// own rays, and its one call of sol_connections every solve (the driver
// inlines each call, a march or a solve each: radiance, path_radiance). q
// and the eye's light positions are in the same coordinates
// (camera-relative in Sol, world in the quotient). Lights as
// sol::lights_at: point lights by the coordinate difference in frame
// components at the hit and 1/(1 + r²) on the distance bound; exact point
// lights (HAS_EXACT_LIGHTS, light_color.w = 2, reach in lights[i].w) along
// each geodesic from q to the light up to the shortest + reach, each with
// 1/J (kLightExactGeodesic) or 1/(1 + L²) on its length L, or as a point
// light where none is found; with shadows, each geodesic's share
// (`pending`) counts where its shadow ray, marched by the caller from q as
// a ray that leaves the surface (kMarchShadow; the CPU's `blocked`), is
// clear. The sum is taken in the order of the lights and their geodesics,
// as the CPU's.
//
// In the quotient (sol::lights_at with the light's images) an exact
// light's connections are those from q (world, in D) to its images of
// length up to d + reach, d the least distance to any image: images are
// taken in order of their distance lower bound from q while that is within
// the least length found + reach (at most kMaxLightImageSolves of them, a
// solve each), their connections kept (the shortest SOL_FOUND_SLOTS), then
// those longer than the least + reach dropped (with 2e-3 of it for the
// float lengths).
struct LightGather {
  vec3 n, q;
  vec3 light;    // the light gathered so far
  vec3 pending;  // the share of the geodesic whose shadow ray is out
  int i;         // the light
  int j, paths;  // an exact light's geodesic j of `paths` (-1: not solved yet)
  vec4 found[SOL_FOUND_SLOTS];
  vec3 target;   // the solve asked for (kGatherSolve): the light seen from q
  float reach;   //   and the reach
  // The quotient's images of light i: solves done, the image last solved
  // (its lower bound and index), the least length found, connections kept.
  int round, last_k, kept;
  float last, best;
};

// What light_gather_step asks of its caller.
const int kGatherDone = 0;    // every light is in g.light
const int kGatherShadow = 1;  // march the shadow ray, then light_gather_blocked
const int kGatherSolve = 2;   // solve g.target's connections up to g.reach, then light_gather_solved

// On to the next light, its connections not solved yet.
void light_gather_next_light(inout LightGather g) {
  ++g.i;
  g.paths = -1;
  g.round = 0;
  g.kept = 0;
  g.last_k = -1;
  g.last = -1.0;
  g.best = 1e30;
}

LightGather light_gather_begin(vec3 n, vec3 q) {
  LightGather g;
  g.n = n;
  g.q = q;
  g.light = vec3(0.0);
  g.pending = vec3(0.0);
  g.j = 0;
  g.target = vec3(0.0);
  g.reach = 0.0;
  g.i = -1;
  light_gather_next_light(g);  // (light 0, its connections not solved yet)
  return g;
}

// The quotient: asks for the solve of light i's next image (true), or
// keeps the connections found within the least + reach (false, g.paths set).
bool quotient_light_round(inout LightGather g, int light, float reach) {
  if (g.round < kMaxLightImageSolves) {
    const int first = params.light_image_first[light], count = params.light_image_count[light];
    const vec2 hq = half_exp(g.q.z);  // shared by the images' bounds
    // The next image by (lower bound, index) after the last one solved.
    float lo = 1e30;
    int lo_k = -1;
    for (int k = 0; k < count; ++k) {
      const vec3 image = light_images[first + k].xyz;
      const float b = distance_lower_bound(g.q, image, hq, half_exp(image.z));
      const bool after = b > g.last || (b == g.last && k > g.last_k);
      if (after && b < lo) {
        lo = b;
        lo_k = k;
      }
    }
    if (lo_k >= 0 && lo <= g.best + reach) {
      g.last = lo;
      g.last_k = lo_k;
      ++g.round;
      const vec3 d = light_images[first + lo_k].xyz - g.q;
      g.target = vec3(exp(-g.q.z) * d.x, exp(g.q.z) * d.y, d.z);
      g.reach = reach;
      return true;
    }
  }
  int m = 0;
  [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) {  // (constant indices: sol_slot_get)
    if (j < g.kept && g.found[j].w <= g.best + reach + 2e-3 * max(1.0, g.best)) sol_slot_set(g.found, m++, g.found[j]);
  }
  g.paths = m;
  g.j = 0;
  return false;
}

// The solve light_gather_step asked for came back: `count` connections in found.
void light_gather_solved(inout LightGather g, int count, vec4 found[SOL_FOUND_SLOTS]) {
  if (!QUOTIENT) {
    g.paths = count;
    g.found = found;
    g.j = 0;
    return;
  }
  [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) {
    if (j >= count) continue;
    g.best = min(g.best, found[j].w);
    if (g.kept < SOL_FOUND_SLOTS) {
      sol_slot_set(g.found, g.kept++, found[j]);
    } else {  // full: replace the longest if this one is shorter
      int longest = 0;
      float longest_length = g.found[0].w;
      [[unroll]] for (int m = 1; m < SOL_FOUND_SLOTS; ++m) {
        if (g.found[m].w > longest_length) {
          longest = m;
          longest_length = g.found[m].w;
        }
      }
      if (found[j].w < longest_length) sol_slot_set(g.found, longest, found[j]);
    }
  }
}

// Gathers g's lights up to the next shadow ray to march (from g.q along
// `direction` up to `len`: kGatherShadow) or connection solve to make
// (kGatherSolve), or to the end (kGatherDone).
int light_gather_step(inout LightGather g, int eye, out vec3 direction, out float len) {
  const int light_count = min(int(params.shading.z), kMaxLights);
  direction = vec3(0.0, 0.0, 1.0);
  len = 0.0;
  // (Loops tested at their end, as everywhere: see march.comp.)
  if (g.i < light_count) do {
    const int i = g.i;
    const vec4 lc = params.light_color[i];
    const vec4 lp = params.eyes[eye].lights[i];
    vec3 l = lp.xyz;
    float attenuation = 1.0;
    if (HAS_POINT_LIGHTS) {
      const vec3 diff = lp.xyz - g.q;
      // q⁻¹·light: the light seen from q, in frame components at q.
      const vec3 towards = vec3(exp(-g.q.z) * diff.x, exp(g.q.z) * diff.y, diff.z);
      if (HAS_EXACT_LIGHTS && (lc.w == float(kLightExactPoint) || lc.w == float(kLightExactGeodesic))) {
        if (g.paths < 0) {
          if (QUOTIENT) {
            if (quotient_light_round(g, i, lp.w)) return kGatherSolve;
          } else {
            g.target = towards;
            g.reach = lp.w;
            return kGatherSolve;
          }
        }
        if (g.j < g.paths) do {
          // found[j]: the geodesic's direction at q and its length; its J seen
          // from q is its J seen from the light (reciprocity).
          const vec4 w = sol_slot_get(g.found, g.j++);
          const float cosine = max(0.0, dot(g.n, w.xyz));
          if (cosine == 0.0) continue;
          const float spread = lc.w == float(kLightExactGeodesic) ? max(sol_sphere_area_density(w.xyz, w.w), kMinSpreading)
                                                                   : 1.0 + w.w * w.w;
          const vec3 share = lc.rgb * (cosine / spread);
          if (HAS_SHADOWS && params.light_shadows[i] != 0) {
            g.pending = share;
            direction = w.xyz;
            len = w.w;
            return kGatherShadow;
          }
          g.light += share;
        } while (g.j < g.paths);
        if (g.paths > 0) {
          light_gather_next_light(g);
          continue;
        }
      }
      const float r = distance_lower_bound(g.q, lp.xyz);
      const bool directional = lc.w == float(kLightDirectional);
      l = directional ? lp.xyz : (length(towards) > 0.0 ? normalize(towards) : vec3(0.0, 0.0, 1.0));
      attenuation = directional ? 1.0 : 1.0 / (1.0 + r * r);
    }
    g.light += lc.rgb * (attenuation * max(0.0, dot(g.n, l)));
    light_gather_next_light(g);
  } while (g.i < light_count);
  return kGatherDone;
}

// light_gather_step with its solves made here (one call of sol_connections):
// true with the next shadow ray, false once every light is in g.light.
bool light_gather_next(inout LightGather g, int eye, out vec3 direction, out float len) {
  int step;
  do {
    step = light_gather_step(g, eye, direction, len);
    // (A constant condition first: without exact lights the specialisation drops the solve.)
    if (HAS_EXACT_LIGHTS && step == kGatherSolve) {
      vec4 found[SOL_FOUND_SLOTS];
      const int count = sol_connections(g.target, g.reach, found);
      light_gather_solved(g, count, found);
    }
  } while (HAS_EXACT_LIGHTS && step == kGatherSolve);
  return step == kGatherShadow;
}

// The shadow ray of light_gather_step's geodesic came back: its share counts where it was clear.
void light_gather_blocked(inout LightGather g, bool blocked) {
  if (!blocked) g.light += g.pending;
}

// The material's lobes at a point of the surface of object k of albedo a
// (sol/materials.h: the dispatch libsol shares).
SolLobes lobes_of(int k, vec3 a) {
  return sol_material_lobes(int(scene_objects[k].material.w), a, scene_objects[k].params);
}

// Object k's image texture at pattern coordinates uv (sol/texture.h's
// texels, bilinear), as sol::texture_color.
vec3 texture_color(int k, vec2 uv) {
  const ivec4 t = scene_objects[k].texture;
  ivec4 at;
  vec2 along;
  sol_texture_taps(uv, scene_objects[k].texture_cells.xy, t.y, t.z, at, along);
  const vec3 top = mix(texels[t.x + at.y * t.y + at.x].rgb, texels[t.x + at.y * t.y + at.z].rgb, along.x);
  const vec3 bottom = mix(texels[t.x + at.w * t.y + at.x].rgb, texels[t.x + at.w * t.y + at.z].rgb, along.x);
  return mix(top, bottom, along.y);
}

// The surface's albedo: its colour times its pattern and its texture.
vec3 albedo(int k, vec2 uv) {
  const vec3 a = scene_objects[k].color.rgb * pattern_factor(int(scene_objects[k].plane.z), uv.x, uv.y);
  return HAS_TEXTURES && scene_objects[k].texture.y > 0 ? a * texture_color(k, uv) : a;
}

// The light object k's surface reflects diffusely where it receives
// `light` (light_gather_next), with plane coordinates uv, before fog
// (radiance_of_hit adds the fog over the arc length).
vec3 diffuse_light(int k, vec2 uv, vec3 light) {
  const float ambient = params.shading.x;
  return albedo(k, uv) * (ambient + (1.0 - ambient) * light);
}

// What a camera ray's hit shows: the scene object, the surface normal
// (frame components), the pattern's coordinates and the world point (the
// AOV's). Planes face the side of the ray's last segment's start; the
// bounds of balls and tubes are left-invariant, so in the quotient their
// gradients along the frame are taken in world coordinates.
struct Surface {
  int object;
  vec3 n;
  vec2 uv;
  vec3 world;
  bool inside;  // a solid seen from inside: its normal turned to face the ray
};

Surface surface_at(MarchHit h) {
  Surface f;
  const vec3 q = h.q;
  int type;
  vec4 rel;
  vec2 heading;
  float radius;
  vec3 phase;
  if (QUOTIENT) {  // the image's record, in world coordinates
    const Image m = images[h.k];
    type = image_type(m);
    rel = m.geometry;
    heading = m.heading.xy;
    radius = m.info.y;
    phase = q;
    f.object = int(m.info.z);
    f.world = q;
  } else {  // the object's, relative to the eye
    if (CROWD) {
      const SeenObject o = crowd_item_seen(h.item);
      type = o.type;
      rel = o.rel;
      heading = o.heading;
      radius = o.radius;
    } else {
      type = g_types[h.k];
      rel = g_relative[h.k];
      heading = g_headings[h.k];
      radius = g_radii[h.k];
    }
    phase = pattern_phase(q, g_eye_camera, g_eye_frac);
    f.object = h.k;
    // World coordinates: camera * q = (x_c + e^{z_c} q.x, y_c + e^{-z_c} q.y, z_c + q.z).
    f.world = g_eye_camera.xyz + vec3(g_eye_camera.w * q.x, g_eye_frac.w * q.y, q.z);
  }
  f.n = HAS_EXACT_BALLS && type == kObjectExactBall && h.exact_k == h.k ? exact_sphere_normal(h.exact_end)
                                                                         : object_normal(type, q, rel, heading, radius, h.from);
  // A solid seen from inside: its normal faces the ray (as the CPU's). An
  // exact ball's where the exact solve's geodesic from the centre is
  // shorter than the radius; another solid's where its bound grows along
  // the ray (it falls towards a surface met from outside): the float
  // march's last step may end a little either side of the surface, where
  // the bound's sign would flip the normal at random.
  f.inside = HAS_INSIDE && ((type == kObjectExactBall && h.exact_k == h.k && h.exact_inside) ||
                            (inside_by_bound(type) && dot(f.n, h.u) > 0.0));
  if (f.inside) f.n = -f.n;
  f.uv = object_pattern_uv(type, q, phase, rel, heading, radius);
  return f;
}

// The fog's transmittance over arc length t.
float fog_transmittance(float t) { return HAS_FOG ? exp(-params.shading.y * t) : 1.0; }

// One hit's share (radiance): over the fog of its segment, its emission and
// its material's diffuse share of its diffuse light, times `weight`;
// returns its material's specular weight times the fog's transmittance,
// and its specular lobe's roughness and index of refraction (`lobe`).
// Written as the CPU's shade_hit (libsol/src/render.cpp) fogs, so that a
// hit without emission or mirror (weight 1) adds exactly the direct light's
// colour.
vec3 radiance_of_hit(MarchHit h, Surface f, vec3 light, vec3 weight, inout vec3 color, out vec2 lobe) {
  const vec4 material = scene_objects[f.object].material;
  const float transmittance = fog_transmittance(h.t);
  const SolLobes lobes = lobes_of(f.object, albedo(f.object, f.uv));
  // (Every hit's light is gathered whatever the diffuse share, as before
  // materials: a light received under `lobes.diffuse > 0.0` made the
  // quotient's reflected rays hit their own surface on lavapipe, which the
  // CPU never does; the cause, the driver or a value the quotient march
  // leaves unset, is not found.)
  const vec3 surface = material.rgb + lobes.diffuse * diffuse_light(f.object, f.uv, light);
  color += weight * (params.fog_color.rgb + (surface - params.fog_color.rgb) * transmittance);
  lobe = vec2(lobes.roughness, lobes.ior);
  return lobes.specular * transmittance;
}

// Where a ray refracted out of a solid (glass, from inside; n its normal
// there, facing the ray before) starts: past the surface it crosses, 3
// hit_epsilon from it along the normal (as the CPU's march_specular: seen
// from inside, a march's pass of the surface it leaves ends where the ray
// heads for a face, which a leaving ray does).
void skip_surface(inout vec3 q, inout vec3 direction, vec3 n) {
  const SolForward s = sol_exp(direction, 3.0 * params.limits.y / max(abs(dot(direction, n)), 0.02));
  q = sol_translate(q, s.position);
  direction = s.direction;
  if (QUOTIENT) {
    float turn = 1.0;
    if (!in_domain(q)) q = teleport(q, false, turn);
    direction.xy *= turn;
  }
}

// The specular lobe's direction at a hit (n: its normal facing the ray; as
// the CPU's specular_direction, drawing the same numbers): a glass's
// refraction or reflection (one number, Fresnel's choice), a glossy lobe's
// (two), else the mirror's reflection (none).
vec3 specular_direction(vec3 u, vec3 n, float roughness, float ior, bool inside, inout uvec2 random) {
  if (ior > 0.0) return sol_dielectric_direction(u, n, ior, inside, path_uniform(random));
  float xi1 = 0.0, xi2 = 0.0;
  if (roughness > 0.0) {
    xi1 = path_uniform(random);
    xi2 = path_uniform(random);
  }
  return sol_specular_direction(u, n, roughness, xi1, xi2);
}

// Direct light from the eye: the camera ray is the first ray radiance's one
// march marches (the host's choice where the march is dear to compile and
// shading marches too: exact balls with shadows or mirrors, sol::vk's
// defer_passes), so that the world's one pipeline holds one march.
const bool DIRECT_FROM_EYE = FROM_EYE_WORLD && !PATH_TRACING && INTEGRATOR == 0;

// What a camera ray brings back where the world has mirrors or glowing
// objects (radiance in libsol/src/render.cpp): at each hit, over the fog of
// its segment, the object's emission, (1 - mirror) times its diffuse light
// and mirror times what the reflected ray brings back (the tangent u
// reflected in the normal, frame components, marched from the hit as a
// ray that leaves its surface), up to max bounces (params.limits.z). One
// call of march for the shadow rays of each hit's lights (light_gather_step)
// and the reflected rays, and one of radiance_of_hit: the driver inlines
// each call, and each holds a march. (Tested at its end: see march.comp.)
// From the eye (DIRECT_FROM_EYE: h.q the ray's start and h.u its
// direction) that march marches the camera ray first; `first` is then what
// it met and `first_f` its surface, where it met one (the AOVs' hit). (The
// specialisation constant alone says which: a pipeline from the eye calls
// radiance from the eye only, and every condition on it folds, so that a
// world without shadows and mirrors keeps no march here.)
vec4 radiance(MarchHit h, Surface f, int eye, uint pixel, out MarchHit first, out Surface first_f) {
  const int bounces = int(params.limits.z);
  vec3 color = vec3(0.0), weight = vec3(1.0);
  int bounce = DIRECT_FROM_EYE ? -1 : 0;  // (the camera ray's segment is no bounce)
  bool alive = true;
  LightGather lights = light_gather_begin(f.n, h.q);
  uvec2 random = uvec2(0u);  // the glossy reflections' numbers, started at the first
  bool random_started = false;
  first = h;
  first_f = f;
  do {
    vec3 direction = h.u;  // (from the eye: the camera ray)
    float len = params.limits.x;
    bool shadow = false;
    if (!DIRECT_FROM_EYE || bounce >= 0) {
      shadow = light_gather_next(lights, eye, direction, len);
      if (!shadow) {  // the hit's light is in: its share, then its reflected ray
        vec2 lobe;
        const vec3 specular = radiance_of_hit(h, f, lights.light, weight, color, lobe);
        weight *= specular;
        alive = HAS_MIRRORS && any(greaterThan(specular, vec3(0.0))) && bounce < bounces;
        if (!alive) break;
        const vec3 n = dot(f.n, h.u) > 0.0 ? -f.n : f.n;
        // A glossy or glass lobe's numbers: the pixel's sample's (as the CPU's radiance).
        if (!random_started && (lobe.x > 0.0 || lobe.y > 0.0)) {
          random = path_random_start(uvec2(params.path.xy), pixel, uint(params.path.z));
          random_started = true;
        }
        direction = specular_direction(h.u, n, lobe.x, lobe.y, f.inside, random);
        if (HAS_INSIDE && lobe.y > 0.0 && f.inside && dot(direction, n) < 0.0) skip_surface(h.q, direction, n);
        len = params.limits.x;
      }
    }
    // (A world without shadows and mirrors marches no ray here: a constant
    // condition, so that the specialisation drops the march; lavapipe would
    // run a march left in, masked, for every pixel. From the eye the camera
    // ray is marched as one: the purpose is then no constant, and the march
    // holds both purposes' branches.)
    if (HAS_SHADOWS || HAS_MIRRORS || DIRECT_FROM_EYE) {
      const MarchHit m = march(h.q, direction, min(len, params.limits.x), kMarchFromStart,
                               DIRECT_FROM_EYE && bounce < 0 ? kMarchCamera : kMarchShadow);
      if (shadow) {
        light_gather_blocked(lights, m.k >= 0);
      } else {
        h = m;
        alive = h.k >= 0;
        if (alive) {
          f = surface_at(h);
          lights = light_gather_begin(f.n, h.q);
        }
        if (DIRECT_FROM_EYE && bounce < 0) {
          first = m;
          first_f = f;
        }
        ++bounce;
      }
    }
  } while (alive);
  return vec4(color, 1.0);
}

#endif  // SOL_MARCH_SHADING_GLSL
