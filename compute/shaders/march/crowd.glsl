// The march through a crowd (CROWD: a Sol world of more than
// kListedObjects objects), the GLSL twin of march_crowd in
// libsol/src/render.cpp: at each step the objects come from the world's
// tree of bounds (sol::BoundsTree, bindings kBindingCrowdNodes and
// kBindingCrowdItems, in world coordinates): a node whose box's distance
// bound from the ray's point is not below the runner-up found so far is
// skipped with all it holds. The nodes and objects are seen from the eye
// as they are read (seen_point, object_seen_from: left translation by the
// eye's position⁻¹ maps a coordinate box to a coordinate box), so the
// march, the shading and the shadow rays stay in the eye's coordinates as
// in a listed world. The surfaces a ray passes (cutout planes between
// their discs, the surface a shadow ray leaves) are a short list of items.
#ifndef SOL_MARCH_CROWD_GLSL
#define SOL_MARCH_CROWD_GLSL

#include "sol/box_bound.h"  // sol_projected_box_distance, shared with libsol

// A crowd's object as the march sees it: its kind's record seen from the
// eye (as a listed world's g_* arrays), its cutout pattern and scene object.
struct SeenObject {
  int type;
  vec4 rel;
  vec2 heading;
  float radius;
  vec2 hc;     // rel.z's half exponentials (half_exp)
  int cutout;  // a cutout plane z = c: its pattern code; else kPatternNone
  int object;  // the scene object (0-based)
};

// Item i's kind (its code), without the rest of its record.
int crowd_item_type(int i) { return int(crowd_items[i].shape.w); }

// Item i (leaf order) seen from the eye of load_objects.
SeenObject crowd_item_seen(int i) {
  const CrowdItem c = crowd_items[i];
  SeenObject o;
  o.type = int(c.shape.w);
  o.rel = c.geometry;
  o.heading = c.shape.xy;
  o.radius = c.shape.z;
  object_seen_from(o.type, o.rel, o.heading, g_eye_camera, g_eye_frac);
  o.hc = c.info.zw * g_eye_half_exp;  // half_exp(rel.z), from the world z's and the eye's
  o.cutout = HAS_CUTOUT ? int(c.info.y) : kPatternNone;
  o.object = int(c.info.x);
  return o;
}

// The distance the march takes for the object at q (hz: q.z's half
// exponentials): its bound, seen from inside where q is inside a solid
// drawn by its bound (`inside`), at least a cutout plane's gap bound.
float crowd_distance(SeenObject o, vec3 q, vec2 hz, out bool inside) {
  const float raw = object_bound(o.type, q, o.rel, o.heading, o.radius, hz, o.hc);
  inside = inside_by_bound(o.type) && raw < 0.0;
  float d = inside ? -raw : raw;
  if (HAS_CUTOUT && o.cutout != kPatternNone) {
    d = max(d, cutout_gap_bound(o.cutout, pattern_phase(q, g_eye_camera, g_eye_frac).xy, g_eye_camera.w * exp(q.z)));
  }
  return d;
}

// Node n's box seen from the eye, and its bound from q (e = (e^{-q_z}, e^{q_z})):
// sol::box_distance_lower_bound in float.
float crowd_node_bound(int n, vec3 q, vec2 e) {
  const CrowdNode node = crowd_nodes[n];
  const vec3 lo = seen_point(node.lo.xyz, g_eye_camera, g_eye_frac);
  const vec3 hi = seen_point(node.hi.xyz, g_eye_camera, g_eye_frac);
  const float gx = max(0.0, max(lo.x - q.x, q.x - hi.x));
  const float gy = max(0.0, max(lo.y - q.y, q.y - hi.y));
  return max(sol_projected_box_distance(gx, q.z, e.x, 1.0, lo.z, hi.z),
             sol_projected_box_distance(gy, q.z, e.y, -1.0, lo.z, hi.z));
}

// One step's nearest objects (sol's StepNearest in libsol/src/render.cpp):
// the least distance and its item, the runner-up's distance, and the least
// two among the hit candidates (the items not being passed: the second for
// where the least is an exact ball's bound and its exact distance is more).
struct CrowdStep {
  float nearest, second, nearest_hit, second_hit;
  int nearest_i, hit_i, second_hit_i;
  bool nearest_inside, hit_inside;
};

CrowdStep crowd_step_none() { return CrowdStep(1e30, 1e30, 1e30, 1e30, 0, 0, 0, false, false); }

void crowd_consider(inout CrowdStep s, int i, float d, bool inside, bool candidate) {
  if (d < s.nearest) {
    s.second = s.nearest;
    s.nearest = d;
    s.nearest_i = i;
    s.nearest_inside = inside;
  } else {
    s.second = min(s.second, d);
  }
  if (candidate && d < s.nearest_hit) {
    s.second_hit = s.nearest_hit;
    s.second_hit_i = s.hit_i;
    s.nearest_hit = d;
    s.hit_i = i;
    s.hit_inside = inside;
  } else if (candidate && d < s.second_hit) {
    s.second_hit = d;
    s.second_hit_i = i;
  }
}

// How near the runner-up a node's bound may be taken for its objects
// (march_crowd's kCrowdCover): seen from above or below a crowd, its
// objects are nearly equidistant.
const float kCrowdCover = 0.8;

bool crowd_passed(ivec4 passed, int i) { return any(equal(passed, ivec4(i))); }

// The tree's search from q (sol::BoundsTree::search, nearer child first):
// every item whose node's bound is below the limit, max(runner-up,
// hit_epsilon), that is not in `passed`, into s; a node no nearer than the
// nearest, within kCrowdCover of the runner-up and clear of hit_epsilon is
// taken whole (its bound as the runner-up). With `starts` instead the
// items within 2 hit_epsilon of q (the surfaces a shadow ray leaves, up to
// four), from the nodes within `reach`. Exact balls count by what their
// solves have shown at arc length t where that is more than their bound
// (`seen`, exact_seen_bound).
void crowd_search(vec3 q, vec2 hz, float hit_epsilon, ivec4 passed, const bool starts, float reach, ExactSeen seen,
                  float t, inout CrowdStep s, inout ivec4 started) {
  const vec2 e = vec2(hz.y * hz.y, hz.x * hz.x);  // e^{-q_z}, e^{q_z}
  int stack_node[kTreeMaxDepth + 2];
  float stack_bound[kTreeMaxDepth + 2];
  int top = 0;
  stack_node[0] = 0;
  stack_bound[0] = crowd_node_bound(0, q, e);
  top = 1;
  float limit = starts ? reach : max(s.second, hit_epsilon);
  int held = 0;
  while (top > 0) {
    --top;
    const int n = stack_node[top];
    const float bound = stack_bound[top];
    if (!(bound < limit)) continue;
    if (!starts && bound >= s.nearest && bound >= kCrowdCover * s.second && bound > 2.0 * hit_epsilon) {
      s.second = min(s.second, bound);  // taken whole
      limit = max(s.second, hit_epsilon);
      continue;
    }
    const CrowdNode node = crowd_nodes[n];
    const int count = int(node.hi.w), first = int(node.lo.w);
    if (count > 0) {
      for (int i = first; i < first + count; ++i) {
        if (starts) {
          bool inside;
          const float d = crowd_distance(crowd_item_seen(i), q, hz, inside);
          if (d < 2.0 * hit_epsilon && held < 4) started[held++] = i;
        } else if (!crowd_passed(passed, i)) {
          bool inside;
          const SeenObject o = crowd_item_seen(i);
          float d = crowd_distance(o, q, hz, inside);
          if (HAS_EXACT_BALLS && o.type == kObjectExactBall) d = exact_seen_bound(seen, i, t, d);
          crowd_consider(s, i, d, inside, true);
          limit = max(s.second, hit_epsilon);
        }
      }
      continue;
    }
    const int a = n + 1, b = first;
    const float da = crowd_node_bound(a, q, e), db = crowd_node_bound(b, q, e);
    // The nearer child on top, visited first.
    const int near_n = da <= db ? a : b, far_n = da <= db ? b : a;
    const float near_d = min(da, db), far_d = max(da, db);
    if (far_d < limit && top < kTreeMaxDepth + 2) {
      stack_node[top] = far_n;
      stack_bound[top++] = far_d;
    }
    if (near_d < limit && top < kTreeMaxDepth + 2) {
      stack_node[top] = near_n;
      stack_bound[top++] = near_d;
    }
  }
}

// One exact solve a step (as quotient_exact_step; each call is inlined, a
// Newton loop each): an exact ball a shadow ray leaves (passed slot
// `leaving`, near its sphere, where its bound is negative on both sides:
// until 2 hit_epsilon away or turned back towards the sphere), else the
// nearest hit candidate, or the nearest item, where it is an exact ball
// whose bound is within kExactShell: its exact distance (inside, where the
// solve landed, -sdf) as the hit candidate's, and as the nearest's its
// exact clearance up to the runner-up (march_exact_step's), noted in
// `seen` at arc length t; a runner-up that is an exact ball is no hit by
// its bound (march_exact_step). Returns the step's length (`step`, the
// bounds', unless the nearest was solved).
float crowd_exact_step(vec3 q, vec3 u, float hit_epsilon, int leaving, float step, float t, inout CrowdStep s,
                       inout ExactSolve exact, inout ExactSeen seen, inout ivec4 passing, inout vec4 leave_signs) {
  int item = -1;
  if (leaving >= 0) {
    item = passing[leaving];
  } else if (s.nearest_hit < kExactShell && crowd_item_type(s.hit_i) == kObjectExactBall) {
    item = s.hit_i;
  } else if (s.nearest < kExactShell && crowd_item_type(s.nearest_i) == kObjectExactBall) {
    item = s.nearest_i;
  }
  if (item < 0) return step;
  const SeenObject o = crowd_item_seen(item);
  const float sdf = exact_ball_sdf(q, o.rel.xyz, o.radius, item, exact);
  const float slope = dot(exact.end.tangent, u);
  const float away = exact.known ? abs(sdf) : 0.0;
  const bool inside = HAS_INSIDE && exact.known && sdf < -hit_epsilon;
  const float beyond = inside ? exact_ball_inside_clearance(away, length(exact.v), slope, hit_epsilon) : away;
  exact_seen_solved(seen, exact.known, item, sdf, t);
  if (leaving >= 0) {
    float leave_sign = leave_signs[leaving];
    if (exact_pass_ends(exact.known, away, slope, hit_epsilon, leave_sign)) passing[leaving] = -1;
    leave_signs[leaving] = leave_sign;
    // (A candidate that is an exact ball, not solved at this step, is no hit.)
    if (crowd_item_type(s.hit_i) == kObjectExactBall) s.nearest_hit = max(s.nearest_hit, hit_epsilon);
    return min(step, beyond);
  }
  const float d = HAS_INSIDE && exact.known ? away : sdf;
  if (item == s.hit_i) {
    const bool nearer = d <= s.second_hit || crowd_item_type(s.second_hit_i) == kObjectExactBall;
    s.nearest_hit = nearer ? d : s.second_hit;
    s.hit_i = nearer ? item : s.second_hit_i;
  }
  if (item != s.nearest_i) return step;
  float clear = d;  // (where the solve did not land: its bound)
  if (exact.known && sdf > hit_epsilon) {
    clear = exact_ball_clearance(d, length(exact.v), slope, hit_epsilon);
  } else if (inside) {
    clear = beyond;
  }
  return min(s.second, clear);
}

// The march of a ray from `origin` (relative to the eye) with unit
// direction `direction` up to arc length `limit` through the crowd (as
// march_sol; closed-form positions, every step's full position). The hit's
// k is the scene object, its `item` the crowd's item.
MarchHit march_crowd(vec3 origin, vec3 direction, float limit, const int purpose) {
  const bool camera = purpose == kMarchCamera;
  const float hit_epsilon = params.limits.y;
  const int max_steps = int(params.limits.w);
  const bool translated = !camera || HAS_ODS || HAS_LENS;
  MarchHit h = march_hit_none(kMarchFromStart);
  h.from = origin;
  SolRay ray = sol_ray(direction);
  sol_ray_integrals(ray);
  ivec4 passing = ivec4(-1);  // the items it passes
  vec4 leave_signs = vec4(0.0);  // for exact balls among them (exact_pass_ends)
  ExactSolve exact = exact_solve_none();
  ExactSeen seen = exact_seen_none();
  if (!camera) {
    // (A solid's distance may be below its box's bound near its surface,
    // where the bound's gradient is short: the boxes within a generous reach.)
    CrowdStep unused = crowd_step_none();
    crowd_search(origin, half_exp(origin.z), hit_epsilon, passing, true, max(2.0 * hit_epsilon, 0.01), seen, 0.0, unused,
                 passing);
    // A solid it leaves through the face it starts on: leave sign 1, its
    // pass ends 2 hit_epsilon away (the CPU's leaving_sign; exact balls'
    // signs are their solves'). A plane z = c it leaves upward: leave sign
    // 1, its pass ends where u_z turns (as march_starts_on's `leaving`).
    for (int j = 0; j < 4; ++j) {
      if (passing[j] < 0) continue;
      const SeenObject o = crowd_item_seen(passing[j]);
      const bool leaves = HAS_INSIDE && leaves_through_start(o.type, origin, direction, o.rel, o.heading, o.radius);
      const bool upward = HAS_PLANES_Z && o.type == kObjectPlaneZ && direction.z > 0.0;
      if (leaves || upward) leave_signs[j] = 1.0;
    }
  }
  float t = 0.0;
  vec3 q = origin, u = direction;
  int hit_item = -1, steps = 0;
  bool ended = false;
  for (int step = 0; step < max_steps; ++step) {
    const SolForward forward = sol_forward(ray, t);
    q = translated ? sol_translate(origin, forward.position) : forward.position;
    u = forward.direction;
    const vec2 hz = half_exp(q.z);
    CrowdStep s = crowd_step_none();
    // The passed surfaces first (until each is 2 hit_epsilon away again,
    // or, seen from inside, the ray heads for a face of it), then the tree.
    const ivec4 passed = passing;
    // The slot of an exact ball it leaves near its sphere: its exact solve
    // decides (the least by exact_seen_bound, so that each is solved in turn).
    int leaving = -1;
    float leaving_d = 1e30;
    for (int j = 0; j < 4; ++j) {
      if (passed[j] < 0) continue;
      const SeenObject o = crowd_item_seen(passed[j]);
      bool inside;
      float d = crowd_distance(o, q, hz, inside);
      const bool exact_ball = HAS_EXACT_BALLS && o.type == kObjectExactBall;
      if (exact_ball) d = exact_seen_bound(seen, passed[j], t, d);
      // Until 2 hit_epsilon out of it, or (a solid not seen from inside)
      // into it (passed_into, sinks_into), or (a plane z = c) where u_z turns, as
      // march_objects.
      const bool turned = HAS_PLANES_Z && o.type == kObjectPlaneZ && (leave_signs[j] > 0.0 ? u.z < 0.0 : u.z > 0.0);
      const bool into = passed_into(o.type, d, hit_epsilon) ||
                        (may_sink_into(o.type, d) &&
                         sinks_into(object_inside_clearances(o.type, q, u, o.rel, o.heading, o.radius, hz, o.hc, -d)));
      bool ends = d > 2.0 * hit_epsilon || into || turned;
      if (exact_ball && !ends && d < kExactShell) {
        if (d < leaving_d) {
          leaving = j;
          leaving_d = d;
        }
        continue;
      }
      if (HAS_INSIDE && inside && d > kHeadsDepth * hit_epsilon && leave_signs[j] <= 0.0) {
        ends = ends || object_inside_clearances(o.type, q, u, o.rel, o.heading, o.radius, hz, o.hc, d).w < 0.0;
      }
      crowd_consider(s, passed[j], d, inside, ends);
      if (ends) passing[j] = -1;
    }
    crowd_search(q, hz, hit_epsilon, passed, false, 0.0, seen, t, s, passing);
    // The nearest solid's clearance along the ray, up to the runner-up
    // (seen from inside: its faces'; object_clearances), as march_sol.
    float nearest = s.nearest;
    const SeenObject o = crowd_item_seen(s.nearest_i);
    if (object_is_solid(o.type)) {
      nearest = min(s.second, max(s.nearest, object_clearance(o.type, q, u, o.rel, o.heading, o.radius, hz, o.hc).y));
    } else if (HAS_PLANES_Z && o.type == kObjectPlaneZ) {
      nearest = min(s.second, max(s.nearest, plane_z_step(q, u, o.rel.x, hit_epsilon)));
    }
    if (HAS_EXACT_BALLS) {
      nearest = crowd_exact_step(q, u, hit_epsilon, leaving, nearest, t, s, exact, seen, passing, leave_signs);
    }
    steps = step + 1;
    if (s.nearest_hit < hit_epsilon) {
      const SeenObject m = crowd_item_seen(s.hit_i);
      bool through = false;
      if (HAS_CUTOUT && m.cutout != kPatternNone) {
        const vec2 uv = object_pattern_uv(m.type, q, pattern_phase(q, g_eye_camera, g_eye_frac), m.rel, m.heading, m.radius);
        through = pattern_factor(m.cutout, uv.x, uv.y) != 1.0;
      }
      if (!through) {
        hit_item = s.hit_i;
        ended = true;
        break;
      }
      // Between the discs: go through.
      for (int j = 0; j < 4; ++j) {
        if (passing[j] < 0) {
          passing[j] = s.hit_i;
          leave_signs[j] = 0.0;
          break;
        }
      }
    }
    const bool any_passed = any(greaterThanEqual(passing, ivec4(0)));
    t += any_passed ? max(nearest, 2.0 * hit_epsilon) : nearest;
    if (t > limit) {
      ended = true;
      break;
    }
  }
  if (!ended) ++g_out_of_steps;
  const int object = hit_item >= 0 ? int(crowd_items[hit_item].info.x) : -1;
  MarchHit found = march_found(object, t, q, origin, steps, exact);
  // Shading takes the exact sphere's normal where the last solve was the hit's.
  const bool solved = HAS_EXACT_BALLS && hit_item >= 0 && exact.k == hit_item;
  found.exact_k = solved ? object : -1;
  found.exact_inside = HAS_INSIDE && solved && exact.known && length(exact.v) < crowd_items[hit_item].shape.z;
  found.item = hit_item;
  found.u = u;
  return found;
}

#endif  // SOL_MARCH_CROWD_GLSL
