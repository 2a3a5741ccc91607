// Planes x = c and y = c in Sol met as roots of their crossing instead of
// marched (the camera rays' march, march.glsl).
#ifndef SOL_MARCH_PLANE_ROOTS_GLSL
#define SOL_MARCH_PLANE_ROOTS_GLSL

// Planes x = c and y = c in Sol, met as roots instead of marched. Along a
// geodesic whose frame components start as (a, b, ·), the momenta conjugate
// to x and y are conserved: x' = a e^{2z}, y' = b e^{-2z} (z relative to the
// start; docs/mathematics.md). So x(t) and y(t) are monotone, such a plane
// is crossed at most once, and its crossing is the one root of x(t) - c (or
// y(t) - c). All of them are solved together, one closed-form position per
// iteration: Newton's step (the derivative is the formula above, from the
// height alone) from the latest point, taken towards the least root it
// predicts, kept inside the bracket [lo, hi] where lo is the latest point
// past no plane and hi the earliest past some (bisection where Newton leaves
// it). It ends as the march does: at a point within `eps` of a plane and
// past no other; or at the limit with none crossed (monotone: none is
// crossed before it). March sphere tracing towards a plane met obliquely
// takes many steps (the sheets preset: 11.8 on average), this a few. When it
// does not end within kPlaneRootIterations the planes are marched as before:
// by the caller's march (`solved` false), or, when every object is such a
// plane (PLANES_XY_ONLY), here, from lo, by their exact distances, within
// `max_steps` more positions. The kernel then has no march loop at all: on
// lavapipe a loop that never runs still costs: its body runs once (sheets:
// 53.8 -> 43.7 ms).
const int kPlaneRootIterations = 16;
struct PlaneRoot {
  bool solved;  // else: march the planes
  int k;        // the plane hit (-1: none within the limit)
  float t;      // its arc length
  vec3 q;       // the point there (coordinates of the march's q)
};
PlaneRoot plane_xy_roots(SolRay ray, vec3 start, int count, int types[kListedObjects], float constants[kListedObjects],
                         float limit, float eps, int max_steps, inout int steps) {
  PlaneRoot r;
  r.solved = true;
  r.k = -1;
  r.t = 1e30;
  r.q = vec3(0.0);
  // x' at q = e^{z_s} a e^{2(q.z - z_s)} = a e^{2 q.z} / e^{z_s}, y' = b e^{z_s} / e^{2 q.z}
  // (the ray starts at `start`, a column's eye, with frame components there).
  const vec3 d = ray.direction;
  const float e_start = exp(start.z);
  uint ahead_mask = 0u;  // the planes ahead of the ray, coming nearer
  float lo = 0.0, hi = limit, t = 0.0;
  bool bracketed = false;  // some plane crossed at hi
  vec3 q = start;
  const int iterations = kPlaneRootIterations + (PLANES_XY_ONLY ? max_steps : 0);
  for (int it = 0; it < iterations; ++it) {
    if (it > 0) {
      q = sol_position_forward(ray, t);
      if (HAS_ODS || HAS_LENS) q = sol_translate(start, q);
      ++steps;
    }
    const float ez = exp(q.z), ez2 = ez * ez;
    const bool marching = PLANES_XY_ONLY && it >= kPlaneRootIterations;
    float least = 1e30;  // the least size over every plane, and its plane: the march's step
    int least_k = -1;
    bool crossed = false, far_crossed = false;
    int near_k = -1;
    float near = eps, ahead = 1e30, behind = 1e30;  // Newton's least predicted root, from before and from past planes
    for (int k = 0; k < count; ++k) {
      const bool is_x = types[k] == kObjectPlaneX;
      if (!is_x && types[k] != kObjectPlaneY) continue;
      const uint bit = 1u << uint(k);
      const float speed = is_x ? d.x : d.y;
      const float gap = (is_x ? q.x : q.y) - constants[k];
      const float f = speed < 0.0 ? -gap : gap;      // rises along the ray; the crossing at f = 0
      const float size = abs(gap) * (is_x ? 1.0 / ez : ez);  // sinh of the distance to the plane
      if (PLANES_XY_ONLY && size < least) {
        least = size;
        least_k = k;
      }
      if (it == 0) {
        if (size < eps) {  // on it at the start: hit there, as the march's first step
          near = size;
          near_k = k;
        }
        if (f < 0.0 && speed != 0.0) ahead_mask |= bit;
      }
      if ((ahead_mask & bit) == 0u) continue;
      const float rate = abs(speed) * (is_x ? ez2 / e_start : e_start / ez2);
      const float root = t - f / rate;
      // Within eps of the plane, as the march's hits, and within eps of its
      // crossing in arc length by Newton's estimate (an oblique ray's point
      // within eps of the plane may lie eps/sin(angle) from it along the ray).
      const bool close = size < eps && abs(f) < rate * eps;
      if (close && size < near) {
        near = size;
        near_k = k;
      }
      if (f >= 0.0) {
        crossed = true;
        far_crossed = far_crossed || !close;
        behind = min(behind, root);
      } else {
        ahead = min(ahead, root);
      }
    }
    if (marching) {
      // Unsettled: the planes marched from lo (past none) by their exact
      // distances asinh(size), as the caller's march would.
      const float nearest = asinh(least);
      if (nearest < eps) {
        r.k = least_k;
        r.t = t;
        r.q = q;
        return r;
      }
      t += nearest;
      if (t > limit) return r;
      continue;
    }
    if (near_k >= 0 && !far_crossed) {  // within eps of a plane, past no other
      r.k = near_k;
      r.t = t;
      r.q = q;
      return r;
    }
    if (ahead_mask == 0u) return r;  // no plane ahead
    if (crossed) {
      hi = t;
      bracketed = true;
    } else {
      if (t >= limit) return r;  // none crossed within the limit
      lo = t;
    }
    float next = crossed ? behind : ahead;
    if (PLANES_XY_ONLY && it + 1 == kPlaneRootIterations) {  // the march from lo next
      t = lo;
      continue;
    }
    if (bracketed) {
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    } else {
      next = min(next, limit);  // no bracket yet: at most the limit
      if (!(next > lo)) next = 0.5 * (lo + limit);
    }
    t = next;
  }
  r.solved = PLANES_XY_ONLY;  // there: out of steps, a miss (as the march)
  return r;
}

#endif  // SOL_MARCH_PLANE_ROOTS_GLSL
