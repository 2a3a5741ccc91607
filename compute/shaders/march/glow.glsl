// Next-event estimation to glowing objects on a path (march/paths.glsl):
// the targets, the points drawn on them and the densities of the
// directions that meet them (glow_sample and glow_density in
// libsol/src/render.cpp, with the same numbers). Included by paths.glsl.
#ifndef SOL_MARCH_GLOW_GLSL
#define SOL_MARCH_GLOW_GLSL

// ---- Next-event estimation to glowing exact balls, boxes, bound balls
// and tubes (glow_sample and glow_density in libsol/src/render.cpp, with
// the same numbers): a target (in Sol a glowing object, in a crowd one of
// its first kListedObjects glowing objects, in a quotient one of its
// images around D: sol::glow_target_objects) picked by glow_pick_weight at x, a point y of
// its surface: an exact ball's y = c·exp(r w), w uniform on S² (area
// density 1 / (4π J_c(w, r))), the other kinds' with the density
// sol/surface_light.h gives in closed form (a tube's over a window about
// x's foot on its axis), connected to the diffuse point
// x by its geodesics up to the distance plus the ball's glow_reach
// (scene_objects[k].glow.x; sol_connections, 0: the minimisers), each
// weighed by its own J (sol_sphere_area_density) and counted where the
// march along it first meets that object at its length; combined with
// reflection sampling by the balance heuristic.
const bool GLOW_BOXES_BALLS = HAS_BOXES || HAS_BOUND_BALLS;  // (one operation a constant: glslang)
const bool GLOW_SURFACES = GLOW_BOXES_BALLS || HAS_TUBES;
const bool GLOW_KINDS = HAS_EXACT_BALLS || GLOW_SURFACES;
const bool GLOW_SAMPLING = HAS_EMISSION && GLOW_KINDS;

// Whether an object of kind `type` emitting `emission` is a target: an
// exact ball, or in Sol a box, a bound ball or a tube about a coordinate
// axis (`aligned`) (in a quotient those are found by reflection, as planes
// everywhere: glow_targets in libsol/src/render.cpp says why).
bool glow_kind(int type, vec3 emission, bool aligned) {
  const bool surface = (HAS_BOXES && type == kObjectBox) || (HAS_BOUND_BALLS && type == kObjectBall) ||
                       (HAS_TUBES && type == kObjectTube && aligned);
  return ((HAS_EXACT_BALLS && type == kObjectExactBall) || (!QUOTIENT && surface)) && emission != vec3(0.0);
}

// A listed tube's axis (sol/surface_light.h: 0 x, 1 y, 2 vertical; -1
// along another horizontal direction) from its record.
int tube_axis_of(vec4 rel, vec2 heading) { return sol_tube_light_axis(int(rel.w) == kTubeVertical, heading.x, heading.y); }
int tube_axis(int k) { return tube_axis_of(g_relative[k], g_headings[k]); }

// The targets: Sol's objects, a crowd's listed targets, or the quotient's images.
int glow_target_slots() { return QUOTIENT ? params.counts.x : (CROWD ? g_crowd_targets : g_count); }

// The target slot of scene object k (a listed world's and a quotient's
// march name their slot; a crowd's its scene object): -1 where none is.
int glow_target_slot(int k) {
  if (!CROWD) return k;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (int(crowd_items[crowd_target_item(i)].info.x) == k) return i;
  }
  return -1;
}

// Scene object k (from the uniforms: a quotient's march loads no g_types;
// a crowd's targets are its listed ones).
bool glowing(int k) {
  if (CROWD) return glow_target_slot(k) >= 0;
  const int type = int(scene_objects[k].plane.x);
  return glow_kind(type, scene_objects[k].material.rgb, type != kObjectTube || (!QUOTIENT && tube_axis(k) >= 0));
}

// The geodesic from q to p (march coordinates) as the connection solver
// takes it: p seen from q, in frame components at q.
vec3 seen_from(vec3 q, vec3 p) {
  const vec3 d = p - q;
  return vec3(exp(-q.z) * d.x, exp(q.z) * d.y, d.z);
}

// A box's half size (a, b, c) from its centre's z and its coordinate half
// widths (A, B) = (a e^{z}, b e^{-z}) there (sol::Box::coordinate_half_widths).
vec3 box_half_size(float z, vec2 widths, float c) { return vec3(widths.x * exp(-z), widths.y * exp(z), c); }

// A target's surface in its own frame w = centre⁻¹·q: its kind, a box's
// half size, a ball's or tube's radius, a tube's axis and the diffuse
// point's distance h to it (which sets the window its points are drawn over).
struct GlowShape {
  int type;
  vec3 half_size;
  float radius;
  int axis;
  float h;
};

// Whether its points' density is known in closed form (sol/surface_light.h:
// a box's, a bound ball's, a tube's), else solved from its centre (an exact ball's).
bool closed_form(GlowShape s) { return GLOW_SURFACES && s.type != kObjectExactBall; }

bool shape_is_tube(GlowShape s) { return HAS_TUBES && s.type == kObjectTube; }

// sol/surface_light.h's functions for a box, a bound ball or a tube.
vec3 shape_point(GlowShape s, float u0, float u1, float u2) {
  if (shape_is_tube(s)) return sol_tube_light_point(s.axis, s.radius, s.h, u0, u1, u2);
  return s.type == kObjectBox ? sol_box_light_point(s.half_size, u0, u1, u2) : sol_ball_light_point(s.radius, u0, u1, u2);
}
vec3 shape_normal(GlowShape s, vec3 w) {
  if (shape_is_tube(s)) return sol_tube_light_normal(s.axis, w, s.radius);
  return s.type == kObjectBox ? sol_box_light_normal(w, s.half_size) : sol_ball_light_normal(w);
}
float shape_density(GlowShape s, vec3 w) {
  if (shape_is_tube(s)) return sol_tube_light_density(s.axis, w, s.radius, s.h);
  return s.type == kObjectBox ? 1.0 / sol_box_light_area(s.half_size) : sol_ball_light_density(w, s.radius);
}
float shape_bound(GlowShape s, vec3 w) {
  if (shape_is_tube(s)) return sol_tube_light_bound(s.axis, w, s.radius);
  return s.type == kObjectBox ? sol_box_light_bound(w, s.half_size) : sol_ball_light_bound(w, s.radius);
}
// A point wy on the face of a box or tube that holds wx: reflection
// sampling's alone (sol_box_light_same_face, sol_tube_light_same_face).
bool shape_skips(GlowShape s, vec3 wx, vec3 wy) {
  if (shape_is_tube(s)) return sol_tube_light_same_face(s.axis, wx, wy, s.radius);
  return s.type == kObjectBox && sol_box_light_same_face(wx, wy, s.half_size);
}

// Target i seen from the diffuse point x: whether it is one, and its scene
// object, centre (march coordinates: a tube's the foot of x on its axis),
// surface and the size it is picked by (a ball's radius, a box's
// sol_box_light_radius, a tube's √(r W)).
bool glow_target(int i, vec3 x, out int object, out vec3 centre, out GlowShape shape, out float size) {
  shape.axis = 0;
  shape.h = 0.0;
  if (QUOTIENT) {
    const Image m = images[i];
    object = int(m.info.z);
    shape.type = image_type(m);
    centre = m.geometry.xyz;
    shape.radius = m.info.y;
    shape.half_size = shape.type == kObjectBox ? box_half_size(centre.z, m.heading.xy, m.geometry.w) : vec3(0.0);
  } else {
    // A listed object's record, or a crowd's target's as the crowd's march sees it.
    vec4 rel;
    vec2 heading;
    if (CROWD) {
      const SeenObject o = crowd_item_seen(crowd_target_item(i));
      object = o.object;
      shape.type = o.type;
      rel = o.rel;
      heading = o.heading;
      shape.radius = o.radius;
    } else {
      object = i;
      shape.type = g_types[i];
      rel = g_relative[i];
      heading = g_headings[i];
      shape.radius = g_radii[i];
    }
    centre = rel.xyz;
    shape.half_size = shape.type == kObjectBox ? box_half_size(centre.z, heading, rel.w) : vec3(0.0);
    if (shape_is_tube(shape)) {
      shape.axis = tube_axis_of(rel, heading);
      centre = sol_tube_light_foot(shape.axis, centre, x);
      shape.h = abs(shape_bound(shape, seen_from(centre, x)));
    }
  }
  size = shape.type == kObjectBox ? sol_box_light_radius(shape.half_size) : shape.radius;
  if (shape_is_tube(shape)) size = sqrt(shape.radius * sol_light_window(shape.h));
  return glow_kind(shape.type, scene_objects[object].material.rgb, shape.axis >= 0);
}

// The surface of the object the march met at h (a listed one, or a
// quotient's image) and its centre (a tube's: the foot of h on its axis).
GlowShape hit_shape(MarchHit h, out vec3 centre) {
  int object;
  GlowShape shape;
  float size;
  glow_target(glow_target_slot(h.k), h.q, object, centre, shape, size);
  return shape;
}

int glowing_count() {
  int n = 0, object;
  vec3 centre;
  GlowShape shape;
  float size;
  for (int i = 0; i < glow_target_slots(); ++i) n += glow_target(i, vec3(0.0), object, centre, shape, size) ? 1 : 0;
  return n;
}

// The weight with which x picks a target of centre c and radius r, about
// its solid angle: r² / (r² + |x⁻¹c|²) (glow_pick_weight).
float glow_pick_weight(vec3 x, vec3 c, float r) {
  const vec3 v = seen_from(x, c);
  return r * r / (r * r + dot(v, v));
}

// The total over the targets seen from x, but the glowing solid whose inner
// wall x lies on (`inside`, its scene object; -1 for none): from there
// every direction meets it or what it holds, and reflection finds its
// light better (glow_pick_weight in libsol/src/render.cpp).
float glow_pick_total(vec3 x, int inside) {
  float total = 0.0, size;
  int object;
  vec3 centre;
  GlowShape shape;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (glow_target(i, x, object, centre, shape, size) && object != inside) total += glow_pick_weight(x, centre, size);
  }
  return total;
}

// The density in solid angle at x with which glow_sample picks direction d
// whose geodesic first meets the glowing scene object k after L, at y on
// the sphere of one of its targets (the nearest; in Sol the hit point, in
// a quotient x exp(L d) in the cover; cos_y: the cosine there with its
// normal): 0 where none holds y, or where that geodesic is longer than the
// distance plus the ball's reach. Its two connection solves (x to y, and
// the target's centre c to y) are path_radiance's (kSolveDensity*), between
// glow_density_target, which finds y, c and r (false: no target holds y),
// and glow_density_of, which takes the second solve's minimiser. Both are
// often known without a solve (glow_density_known): the geodesic from x
// is the minimiser where it is shorter than its period (`minimiser`), and
// the march that met the sphere solved the geodesic from its centre to
// the hit (`from_centre`: its unit direction and length; w = 0: unknown).
struct GlowDensity {
  int k;
  int inside;  // the solid whose inner wall x lies on (no target from there), or -1
  vec3 x, d, y, c;
  float L, r, cos_y;
  GlowShape shape;  // the target's surface (closed_form: its area density needs no solve from the centre)
  bool minimiser;
  vec4 from_centre;
};

// The cosine at the hit h on a box or bound ball between the march's
// tangent and the surface's exact normal there (sol/surface_light.h; the
// CPU's is the cover's geodesic against the cover's surface, the same
// angle), not the bound's gradient by differences.
float surface_hit_cosine(MarchHit h) {
  vec3 centre;
  const GlowShape shape = hit_shape(h, centre);
  return abs(dot(h.u, shape_normal(shape, seen_from(centre, h.q))));
}

// What the march that met the ball at h already shows (GlowDensity's
// `minimiser` and `from_centre`): a geodesic of length L shorter than its
// period by the float margin is the unique minimiser (Coiculescu–Schwartz;
// sol_connections' certificate), whatever the reach; and the march's last
// exact solve, where it is the hit's and lands on the sphere (its length
// the radius within the density's tolerance below), is the minimiser from
// the centre: in a quotient from the image the march met, whose frame may
// be turned by Γ (a half turn, under which J is unchanged).
void glow_density_known(MarchHit h, inout GlowDensity q) {
  q.minimiser = q.L < (1.0 - kMinimiserMargin) * sol_cut_time(q.d);
  const float len = length(h.exact_v);
  const bool solved = h.exact_k >= 0 && h.exact_k == h.k && abs(len - q.r) <= 1e-3 * max(1.0, q.r);
  q.from_centre = solved ? vec4(h.exact_v / len, len) : vec4(0.0);
}

bool glow_density_target(int k, vec3 x, int inside, vec3 d, float L, vec3 hit, float cos_y, out GlowDensity q) {
  q.k = k;
  q.inside = inside;
  q.x = x;
  q.d = d;
  q.L = L;
  q.cos_y = cos_y;
  q.minimiser = false;
  q.from_centre = vec4(0.0);
  q.y = QUOTIENT ? sol_translate(x, sol_spread(d, L).position) : hit;
  q.c = vec3(0.0);
  q.r = 0.0;
  q.shape = GlowShape(kObjectExactBall, vec3(0.0), 0.0, 0, 0.0);
  vec3 centre;
  GlowShape shape;
  float size, nearest = 1e30;
  int object;
  // The nearest target: an exact ball's by its centre, a box's or bound ball's by its bound
  // (none where x lies on the inner wall of k: no target from there).
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (!glow_target(i, x, object, centre, shape, size) || object != k || object == inside) continue;
    const vec3 v = seen_from(centre, q.y);
    const float offset = closed_form(shape) ? abs(shape_bound(shape, v)) : dot(v, v);
    if (offset < nearest) {
      nearest = offset;
      q.c = centre;
      q.r = size;
      q.shape = shape;
    }
  }
  // (A box's or bound ball's image holds y where y lies on its surface, to
  // the march's tolerance, and x not on y's face; an exact ball's is checked later.)
  if (closed_form(q.shape)) return nearest <= 1e-3 && !shape_skips(q.shape, seen_from(q.c, q.x), seen_from(q.c, q.y));
  return nearest < 1e30;
}

// The first solve's verdict: whether the geodesic of length L is within the
// ball's reach of the minimiser from x to y (`count` connections, found[0]
// the shortest).
bool glow_density_reached(GlowDensity q, int count, vec4 shortest) {
  return count > 0 && !(q.L > (shortest.w + scene_objects[q.k].glow.x) * (1.0 + 1e-3) + 1e-4);
}

// The density from the second solve (an exact ball's minimiser from c to
// y; a box's or bound ball's needs none: its area density is closed_form).
float glow_density_of(GlowDensity q, int count, vec4 shortest) {
  const bool box = closed_form(q.shape);
  if (!box && (count == 0 || abs(shortest.w - q.r) > 1e-3 * max(1.0, q.r))) return 0.0;
  if (!(q.cos_y > 0.0)) return 0.0;
  // The spreading from the centre to y (a ball's), then from x to y: one call
  // of sol_sphere_area_density in a loop whose count the compiler cannot fold.
  float spreading[2];
  spreading[0] = 1.0;
  int i = box ? 1 : 0;
  do {
    spreading[i] = sol_sphere_area_density(i == 0 ? shortest.xyz : q.d, i == 0 ? q.r : q.L);
  } while (++i < count + 1 && spreading[0] > 0.0 && i < 2);
  const float area = box ? shape_density(q.shape, seen_from(q.c, q.y)) : 1.0 / (4.0 * SOL_PI * spreading[0]);
  if (!(spreading[0] > 0.0)) return 0.0;
  const float pick = glow_pick_weight(q.x, q.c, q.r) / glow_pick_total(q.x, q.inside);
  return pick * area * spreading[1] / q.cos_y;
}

// One sampled point of one glowing object seen from a diffuse hit: the
// object (its scene object k), the normal at x and at y, the area density,
// the path's weight times the albedo there, and the geodesics to y within
// reach, which path_radiance marches one by one (glow_connection).
struct GlowSample {
  int k;
  vec3 n;         // the normal at x, facing the ray that came
  vec3 normal_y;  // the surface's outward normal at y
  float area;     // the density of y per unit area (with the pick's)
  vec3 factor;    // the path's weight times the albedo at x
  vec3 towards;   // y seen from x (frame components at x): the target of its connections' solve
  int count;      // geodesics in `ways`
  vec4 ways[SOL_FOUND_SLOTS];
  bool skip;      // no point drawn (no target from x), or y on the face of a box or tube that holds x (shape_skips)
};

// Whether the hit h lies on the inner wall of an exact ball of radius
// below kConvexBallRadius (in Sol among listed objects: MARCH_SKIPS).
bool on_convex_ball_inside(MarchHit h) {
  return MARCH_SKIPS && h.k >= 0 && h.exact_k == h.k && h.exact_inside && g_types[h.k] == kObjectExactBall &&
         g_radii[h.k] < kConvexBallRadius;
}

// Draws a target and a point y of its sphere at the diffuse hit h (normal
// n; on the inner wall of the scene object `inside`, which is no target
// from there, or -1); the geodesics from h to y within its reach are
// path_radiance's solve (kSolveGlowSample).
GlowSample glow_sample(MarchHit h, vec3 n, vec3 factor, int inside, inout uvec2 state) {
  GlowSample g;
  g.n = n;
  g.factor = factor;
  g.count = 0;
  g.k = -1;
  const float total = glow_pick_total(h.q, inside);
  g.skip = !(total > 0.0);  // no target from here
  if (g.skip) return g;
  float left = path_uniform(state) * total, weight_k = 0.0;
  int object;
  vec3 c = vec3(0.0), centre;
  GlowShape picked = GlowShape(kObjectExactBall, vec3(0.0), 0.0, 0, 0.0), shape;
  float size;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (!glow_target(i, h.q, object, centre, shape, size) || object == inside) continue;
    const float w = glow_pick_weight(h.q, centre, size);
    if (g.k < 0 || left >= 0.0) {  // the first target, then each the remaining share still reaches
      g.k = object;
      c = centre;
      picked = shape;
      weight_k = w;
    }
    left -= w;
  }
  vec3 y;
  if (closed_form(picked)) {  // a box's, bound ball's or tube's point (sol/surface_light.h)
    const float u0 = path_uniform(state), u1 = path_uniform(state), u2 = path_uniform(state);
    const vec3 w = shape_point(picked, u0, u1, u2);
    y = sol_translate(c, w);
    g.normal_y = shape_normal(picked, w);
    g.area = weight_k / total * shape_density(picked, w);
    g.skip = shape_skips(picked, seen_from(c, h.q), w);
  } else {
    const float u = 2.0 * path_uniform(state) - 1.0, phi = 2.0 * SOL_PI * path_uniform(state);
    const float s = sqrt(max(0.0, 1.0 - u * u));
    const vec3 w = vec3(s * cos(phi), s * sin(phi), u);
    const SolSpread on_sphere = sol_spread(w, picked.radius);  // the point, its normal and its J in one integration
    y = sol_translate(c, on_sphere.position);
    g.normal_y = on_sphere.direction;
    g.area = weight_k / total / (4.0 * SOL_PI * max(on_sphere.density, 1e-30));
  }
  g.towards = seen_from(h.q, y);
  return g;
}

#endif  // SOL_MARCH_GLOW_GLSL
