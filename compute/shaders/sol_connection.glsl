// The geodesics from the origin to a point w in float (the inverse of the
// exponential map): the kernels' part of sol::geodesics_between, for exact
// point lights (w = p⁻¹·L: by left-invariance the directions at the origin
// are the directions at the hit point p in frame components).
//
// The kernel has neither the scan nor the homotopy of libsol's solver. It
// takes the seeds of the cell of sol::ConnectionTable that holds the target
// (the connections at its eight corners, found by the double solver) and
// polishes each by Newton's method on v = t·(a, b, c), the initial vector of
// the exponential map, through the float closed form of sol_geodesic.glsl:
// the Jacobian from the Jacobi fields (sol_spreading.glsl), steps capped
// and halved while the residual grows. A polished seed is a connection
// when its end point lies within the float tolerance of w (measured in
// frame components at w). What that finds
// and how accurately: tests vk.Kernel.Connections* and docs/exact.md "Exact spheres
// and point lights in the renderer".
//
// Needs sol_geodesic.glsl, and before this file a storage buffer
//   vec4 connection_seeds[];  // sol::ConnectionTable::seeds
// The table's geometry (kSeed*) is sol::ConnectionTable's, from
// sol/kernel_constants.h.

#include "sol/kernel_constants.h"
#include "sol/log_series.h"  // sol_log_series
#include "sol_spreading.glsl"  // sol_exp_jacobian

// Whether sol_connections looks for fold partners when given a reach: a
// constant the including kernel may set (march.comp: its specialisation
// constant for lights with a reach), so that kernels without a reach do not
// carry that code; on by default.
#ifndef SOL_FOLD_PARTNERS
#define SOL_FOLD_PARTNERS true
#endif

// How many connections a search keeps (the shortest; at most kSeedSlots):
// a preprocessor constant the including kernel may set (an array size: a
// specialisation constant cannot size arrays that are copied). Without a
// reach only the minimisers count (two on the cut locus, and within the
// float tolerance of their length a third past its conjugate point): 4
// keep them. lavapipe keeps these arrays in per-lane memory; at 16 slots
// the light of `spheres` cost 15 % more. Default: all.
#ifndef SOL_FOUND_SLOTS
#define SOL_FOUND_SLOTS kSeedSlots
#endif

// A list of connections read and written at a varying index j: by a loop
// over the slots that compares each with j, unrolled, so that every access
// has a constant index. lavapipe turns an access at a varying index into a
// branch per slot, and with the lists carried through the kernel's loops
// the reach build (16 slots) compiled several times slower.
vec4 sol_slot_get(vec4 list[SOL_FOUND_SLOTS], int j) {
  vec4 v = vec4(0.0);
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) v = i == j ? list[i] : v;
  return v;
}
void sol_slot_set(inout vec4 list[SOL_FOUND_SLOTS], int j, vec4 v) {
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) list[i] = i == j ? v : list[i];
}
float sol_slot_get(float list[SOL_FOUND_SLOTS], int j) {
  float v = 0.0;
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) v = i == j ? list[i] : v;
  return v;
}
void sol_slot_set(inout float list[SOL_FOUND_SLOTS], int j, float v) {
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) list[i] = i == j ? v : list[i];
}

// Newton's iterations (accepted steps) at most: near the cut locus, where
// the Jacobian is nearly singular, 8 left some connections short of the
// float floor.
const int SOL_NEWTON_ITERATIONS = 16;
// A seed within SOL_SEED_SKIP max(1, t) of a connection already found (in
// t·(a, b, c)) is not polished: it would find that connection again.
const float SOL_SEED_SKIP = 0.25;

// The end of a connection: exp(v), and the geodesic's unit tangent there
// (frame components: at the far end of the geodesic from the origin, the
// gradient of the distance from the origin where it minimises).
struct SolEnd {
  vec3 point;
  vec3 tangent;
};

// The exponential map at the origin: the end of the geodesic with initial
// vector v. Forward (t >= 0): sol_ray_integrals's start-to-end-of-quarter
// piece is the far piece, and the far and near pieces are taken for one
// coordinate (sol_forward): three single R_D in all (the lower quarter,
// the far piece, the near piece), where sol_position would take four pairs.
SolEnd sol_exp_end(vec3 v) {
  SolEnd e;
  e.point = vec3(0.0);
  e.tangent = vec3(0.0, 0.0, 1.0);
  const float t = length(v);
  if (!(t > 0.0)) return e;
  SolRay g = sol_ray(v / t);
  sol_ray_integrals(g);
  const SolForward f = sol_forward(g, t);
  e.point = f.position;
  e.tangent = f.direction;
  return e;
}

vec3 sol_exp(vec3 v) { return sol_exp_end(v).point; }

// exp(v) - w in frame components at w (e^{z} = ez there).
vec3 sol_connection_residual(vec3 v, vec3 w, float ez) {
  const vec3 d = sol_exp(v) - w;
  return vec3(d.x / ez, d.y * ez, d.z);
}

// The float rounding floor of a residual at w: the closed form's error is
// relative to the coordinates (tests Kernel.FlowMatchesTheDoubleClosedForm),
// and frame components at w scale x by e^{-z}, y by e^{z}.
float sol_connection_scale(vec3 w, float ez, float t) {
  return max(max(1.0, t), max(max(abs(w.x) / ez, abs(w.y) * ez), abs(w.z)));
}

// Newton's method from v towards w, steps capped and halved (up to 3
// times) while the residual grows; `residual` receives the final
// |exp(v) - w| (frame components at w) over sol_connection_scale. Every
// iteration takes the Jacobian at v from the Jacobi fields
// (sol_exp_jacobian: products and sums) and one closed-form evaluation, at
// the trial v + dv. When `known`, `end` = exp(v) (a solve at a nearby w,
// the march's last), so the first residual costs no evaluation; else the
// first iteration evaluates v itself. v, end and known leave holding the
// last solution (known: end = exp(v)). Written as one loop with a single
// call of the closed form: Mesa compiles every inlined call of it
// separately, and one call site keeps lavapipe's compile time in seconds;
// and lavapipe runs code its lanes all skip, masked, so a separate first
// evaluation before the loop would cost every SIMD group that shades no hit
// a whole evaluation. (The Jacobian by forward differences, three
// evaluations, or by Broyden's updates for the march's exact balls took
// 14.8 evaluations per lit hit of `spheres`, against 4.4 with it, each
// with its Jacobian; 16.5 per hit for its exact balls, against 8.2.)
vec3 sol_newton(vec3 v, vec3 w, inout SolEnd end, inout bool known, inout mat3 J, out float residual) {
  const float ez = exp(w.z);
  const vec3 to_frame = vec3(1.0 / ez, ez, 1.0);  // frame components at w
  vec3 r = (end.point - w) * to_frame, dv = vec3(0.0);
  int iterations = 0, halvings = 0;
  bool done = known && length(r) < 2e-6 * sol_connection_scale(w, ez, length(v));
  // Given a solution (`known`), J is the last solve's Jacobian, taken near
  // v: the first step is taken with it (a chord step), and only where that
  // does not lower the residual with a fresh one.
  bool chord = known;
  int e = 0;  // (tested at its end: see the top of march.comp)
  if (!done) do {
    if (known && halvings == 0) {  // a step from r and the Jacobian at v
      if (!chord) J = sol_exp_jacobian(v, end.point.z, w.z);
      if (!(abs(determinant(J)) > 1e-12)) break;  // singular: a conjugate point (or NaN)
      dv = -(inverse(J) * r);
      const float cap = 0.5 * max(1.0, length(v));
      if (length(dv) > cap) dv *= cap / length(dv);
    }
    const vec3 at = known ? v + dv : v;
    const SolEnd at_end = sol_exp_end(at);
    const vec3 f = (at_end.point - w) * to_frame;
    if (known && !(length(f) < length(r))) {
      if (chord) {  // the old Jacobian did not help: a fresh one
        chord = false;
        continue;
      }
      dv *= 0.5;  // no better: halve the step, or give up
      done = ++halvings > 3;
      continue;
    }
    chord = false;
    iterations += known ? 1 : 0;
    known = true;
    halvings = 0;
    v = at;
    r = f;
    end = at_end;
    // At the float floor, or out of iterations: done; else a step.
    done = length(r) < 2e-6 * sol_connection_scale(w, ez, length(v)) || iterations == SOL_NEWTON_ITERATIONS;
  } while (++e < 3 * SOL_NEWTON_ITERATIONS + 1 && !done);
  residual = known ? length(r) / sol_connection_scale(w, ez, length(v)) : 1e30;
  return v;
}

// sol_newton from v alone.
vec3 sol_polish(vec3 v, vec3 w, out float residual) {
  SolEnd end;
  end.point = vec3(0.0);
  end.tangent = vec3(0.0, 0.0, 1.0);
  bool known = false;
  mat3 J = mat3(1.0);  // (unused: no solution given)
  return sol_newton(v, w, end, known, J, residual);
}

// The index of the first seed of the table's cell holding `target` (w with
// |x|, |y|: the symmetries give the other signs); targets outside the grid
// take the nearest cell's.
int sol_seed_base(vec3 target) {
  const vec3 g = vec3(asinh(target.x), asinh(target.y), target.z + kSeedHeight) / kSeedStep;
  const ivec3 cell = clamp(ivec3(floor(g)), ivec3(0), ivec3(kSeedCellsXY - 1, kSeedCellsXY - 1, kSeedCellsZ - 1));
  return ((cell.z * kSeedCellsXY + cell.y) * kSeedCellsXY + cell.x) * kSeedSlots;
}

// Adds the polished vector v to the connections found (sorted by length,
// the shortest SOL_FOUND_SLOTS) when it converged and is new; a connection
// found twice keeps the better polished copy.
void sol_add_connection(vec3 v, float residual, inout vec4 found[SOL_FOUND_SLOTS], inout float residuals[SOL_FOUND_SLOTS],
                        inout int count) {
  const float t = length(v);
  if (!(residual < 2e-4) || !(t > 0.0)) return;
  vec4 c = vec4(v / t, t);
  float c_residual = residual;
  int same = -1;
  [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) {
    if (j < count && dot(found[j].xyz, c.xyz) > 1.0 - 5e-7 && abs(found[j].w - t) < 2e-4 * max(1.0, t)) same = j;
  }
  if (same >= 0) {
    if (c_residual < sol_slot_get(residuals, same)) {
      sol_slot_set(found, same, c);
      sol_slot_set(residuals, same, c_residual);
    }
    return;
  }
  // Insert in order of length; when all slots are taken, the longest of
  // them and c (left in c) drops out.
  [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) {
    if (j < count && found[j].w > c.w) {
      const vec4 held = found[j];
      const float held_residual = residuals[j];
      found[j] = c;
      residuals[j] = c_residual;
      c = held;
      c_residual = held_residual;
    }
  }
  if (count < SOL_FOUND_SLOTS) {
    sol_slot_set(found, count, c);
    sol_slot_set(residuals, count, c_residual);
    ++count;
  }
}

// A connection clearly shorter than its period (by the float margin
// kMinimiserMargin, relative) is the unique minimiser: a second geodesic
// of the same length would cut it before its period.
const float kMinimiserMargin = 1e-3;
// The residual (over its float floor, sol_newton) of a polish that ended at
// the floor rather than out of iterations.
const float kMinimiserPolish = 1e-5;

// A seed for the fold partner of the connection v (0 when v is not near a
// fold): with J the Jacobian of the residual F at v, n its right singular
// vector of the smallest singular value σ (inverse iteration on JᵀJ) and
// u = J n / σ, F(v + x n)·u ≈ σ x + κ x²/2 along n (κ by central
// differences), whose other root x = -2σ/κ is where the partner lies. One
// call of the closed form, as in sol_polish.
vec3 sol_fold_partner(vec3 v, vec3 w) {
  const float ez = exp(w.z);
  const float scale = max(1.0, length(v));
  const float h = 1e-3 * scale, step = 0.05 * scale;
  vec3 r = vec3(0.0), n = vec3(0.0), Jn = vec3(0.0), curvature = vec3(0.0);
  mat3 J;
  for (int e = 0; e < 6; ++e) {
    vec3 at = v;
    if (e >= 1 && e <= 3) at[e - 1] += h;
    if (e >= 4) at += (e == 4 ? step : -step) * n;
    const vec3 f = sol_connection_residual(at, w, ez);
    if (e == 0) r = f;
    if (e >= 1 && e <= 3) J[e - 1] = (f - r) / h;
    if (e == 3) {
      const mat3 JtJ = transpose(J) * J;
      if (!(abs(determinant(JtJ)) > 1e-20)) return vec3(0.0);
      const mat3 M = inverse(JtJ);
      n = vec3(0.6, 0.5, 0.62);
      for (int i = 0; i < 4; ++i) n = normalize(M * n);
      Jn = J * n;
    }
    if (e >= 4) curvature += f - r;
  }
  const float sigma = length(Jn);
  const float kappa = dot(Jn / sigma, curvature) / (step * step);
  const float x = -2.0 * sigma / kappa;
  // Far from a fold the partner is either no connection or a seed of its own.
  if (!(abs(x) < 0.5 * scale) || !(abs(x) > 1e-3 * scale)) return vec3(0.0);
  return v + x * n;
}

// The connections from the origin to w (at most SOL_FOUND_SLOTS), shortest
// first, as (unit direction, length), up to the shortest one found + reach;
// returns how many. None when w = 0, or when no seed converges (far outside
// the table, or at a fold where the seeds' connections vanish): the caller
// then keeps the coordinate approximation, as sol::lights_at does when the
// solver gives up.
int sol_connections(vec3 w, float reach, out vec4 found[SOL_FOUND_SLOTS]) {
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) found[i] = vec4(0.0);
  const vec3 target = vec3(abs(w.x), abs(w.y), w.z);
  const vec3 sign_xy = vec3(w.x < 0.0 ? -1.0 : 1.0, w.y < 0.0 ? -1.0 : 1.0, 1.0);
  if (target.x == 0.0 && target.y == 0.0) {  // the vertical line, the only connection
    if (w.z == 0.0) return 0;
    found[0] = vec4(0.0, 0.0, sign(w.z), abs(w.z));
    return 1;
  }
  const int base = sol_seed_base(target);
  int count = 0;
  float residuals[SOL_FOUND_SLOTS];
  // Candidates: the cell's seeds, then (with a reach: the longer
  // connections) a fold partner of each connection the seeds found. Near a
  // fold (a caustic) connections come in pairs that merge there, and a pair
  // born inside a table cell has seeds at none of its corners. One call of
  // sol_polish (see there).
  vec4 originals[SOL_FOUND_SLOTS];
  int first = -1;
  for (int s = 0; s < 2 * kSeedSlots; ++s) {
    vec3 start = vec3(0.0);
    if (s < kSeedSlots) {
      const vec4 seed = connection_seeds[base + s];
      if (seed.w == 0.0) {  // slots are filled in order: on to the partners
        s = kSeedSlots - 1;
        continue;
      }
      start = seed.xyz * seed.w;
      // A seed next to a connection already found would only find it again.
      bool known = false;
      [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) {
        known = known || (j < count && length(found[j].xyz * found[j].w - start) < SOL_SEED_SKIP * max(1.0, seed.w));
      }
      if (known) continue;
    } else {
      if (!SOL_FOLD_PARTNERS || !(reach > 0.0)) break;
      if (first < 0) {
        first = count;
        originals = found;  // the inserts below reorder found
      }
      const int j = s - kSeedSlots;
      if (j >= first) break;
      const vec4 original = sol_slot_get(originals, j);
      if (original.w > originals[0].w + reach) continue;  // beyond the reach, and its partner too
      start = sol_fold_partner(original.xyz * original.w, target);
      if (start == vec3(0.0)) continue;
    }
    float residual;
    const vec3 v = sol_polish(start, target, residual);
    sol_add_connection(v, residual, found, residuals, count);
    // Without a reach only the minimisers count: once the shortest found is
    // certified the unique one (shorter than its period) and polished to
    // the float floor, the other seeds could only find longer connections
    // (or polish it again). Next to the cut locus (two minimisers, the
    // length near the period) every seed is polished.
    if (!(reach > 0.0) && count > 0 && residuals[0] < kMinimiserPolish &&
        found[0].w < (1.0 - kMinimiserMargin) * sol_cut_time(found[0].xyz)) {
      break;
    }
  }
  int kept = 0;
  [[unroll]] for (int i = 0; i < SOL_FOUND_SLOTS; ++i) {
    if (i >= count) continue;
    // Longer connections within the float tolerance of the limit count in.
    if (found[i].w <= found[0].w + reach + 1e-4 * max(1.0, found[i].w)) {
      found[i].xyz *= sign_xy;
      ++kept;
    } else {
      found[i] = vec4(0.0);
    }
  }
  return kept;
}

// The shortest geodesic from the origin to w, as its initial vector v (|v|
// the distance; for exact balls, march/exact_balls.glsl). Newton (sol_newton) starts
// - within the reach of the logarithm's series (|w| < kLogSeriesReach,
//   sol/log_series.h), from the series at w, within 5e-5 of the solution
//   (float rounding is then one Newton step away, or none), and when `v`
//   is given (`known`: the solution at a nearby point, the march's last,
//   with `end` its end point), from v moved by the series' difference
//   between w and that end point, whose error is the series' error's
//   change over that short way (measured: 1.06 evaluations a solve on
//   `spheres`, where the step from v with the last Jacobian took 1.77);
// - else from `v` when it is given;
// - else from the shortest seed of w's cell of the table (a minimiser at
//   one of its corners), else from the Euclidean guess in the frame at the
//   middle height.
// Where that does not land (a far point, whose cell's first seed lies
// outside Newton's reach), every other seed of the cell is polished and
// the shortest landing is kept. One call of sol_newton in the loop: see
// sol_newton. Returns the residual over its float floor; below 2e-4 the
// solution lands on w.
float sol_shortest(vec3 w, inout vec3 v, inout SolEnd end, inout bool known, inout mat3 J) {
  const vec3 target = vec3(abs(w.x), abs(w.y), w.z);
  const int base = sol_seed_base(target);
  const vec3 sign_xy = vec3(w.x < 0.0 ? -1.0 : 1.0, w.y < 0.0 ? -1.0 : 1.0, 1.0);
  float best = 1e30, best_residual = 1e30;
  vec3 best_v = v;
  SolEnd best_end = end;
  mat3 best_J = J;
  const bool series = length(w) < kLogSeriesReach && (!known || length(end.point) < kLogSeriesReach);
  for (int s = known || series ? -1 : 0; s < kSeedSlots; ++s) {
    vec3 start = v;
    SolEnd at_end = end;
    mat3 at_J = J;
    bool carried = s < 0;
    if (carried && series) {  // from the series (evaluated first: not carried)
      start = known ? v + (sol_log_series(w) - sol_log_series(end.point)) : sol_log_series(w);
      carried = false;
    } else if (!carried) {
      const vec4 seed = connection_seeds[base + s];
      if (s > 0 && seed.w == 0.0) break;  // slots are filled in order
      start = seed.w > 0.0 ? seed.xyz * seed.w * sign_xy : vec3(w.x * exp(-0.5 * w.z), w.y * exp(0.5 * w.z), w.z);
    }
    float residual;
    const vec3 found = sol_newton(start, w, at_end, carried, at_J, residual);
    if (residual < 2e-4 ? (best_residual >= 2e-4 || length(found) < best) : residual < best_residual && best_residual >= 2e-4) {
      best = length(found);
      best_residual = residual;
      best_v = found;
      best_end = at_end;
      best_J = at_J;
    }
    if (s <= 0 && residual < 2e-4) break;  // the usual case: one solve
  }
  v = best_v;
  end = best_end;
  J = best_J;
  known = best_residual < 2e-4;
  return best_residual;
}
