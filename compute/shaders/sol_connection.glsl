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
// forward-difference Jacobian, steps capped and halved while the residual
// grows. A polished seed is a connection when its end point lies within the
// float tolerance of w (measured in frame components at w). What that finds
// and how accurately: tests vk.Kernel.Connections* and README "Exact spheres
// and point lights".
//
// Needs sol_geodesic.glsl, and before this file a storage buffer
//   vec4 connection_seeds[];  // sol::ConnectionTable::seeds
// Keep the constants in step with sol::ConnectionTable (connection.hpp).

const int SOL_SEED_SLOTS = 16;
const int SOL_SEED_CELLS_XY = 10;
const int SOL_SEED_CELLS_Z = 16;
const float SOL_SEED_STEP = 0.5;
const float SOL_SEED_HEIGHT = 4.0;
const int SOL_NEWTON_ITERATIONS = 8;
#ifndef SOL_SEED_SKIP
#define SOL_SEED_SKIP 0.25
#endif

// The exponential map at the origin: the end of the geodesic with initial vector v.
vec3 sol_exp(vec3 v) {
  const float t = length(v);
  if (!(t > 0.0)) return vec3(0.0);
  SolRay g = sol_ray(v / t);
  sol_ray_integrals(g);
  return sol_position(g, t);
}

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

// Newton's method from v towards w; `residual` receives the final |exp(v) - w|
// (frame components at w) divided by sol_connection_scale.
vec3 sol_polish(vec3 v, vec3 w, out float residual) {
  const float ez = exp(w.z);
  vec3 r = sol_connection_residual(v, w, ez);
  float scale = sol_connection_scale(w, ez, length(v));
  for (int it = 0; it < SOL_NEWTON_ITERATIONS; ++it) {
    if (length(r) < 2e-6 * scale) break;  // at the float floor
    const float h = 1e-3 * max(1.0, length(v));
    mat3 J;
    J[0] = (sol_connection_residual(v + vec3(h, 0.0, 0.0), w, ez) - r) / h;
    J[1] = (sol_connection_residual(v + vec3(0.0, h, 0.0), w, ez) - r) / h;
    J[2] = (sol_connection_residual(v + vec3(0.0, 0.0, h), w, ez) - r) / h;
    const float det = determinant(J);
    if (!(abs(det) > 1e-12)) break;  // a conjugate point (or NaN): give up
    vec3 dv = -(inverse(J) * r);
    const float cap = 0.5 * max(1.0, length(v));
    if (length(dv) > cap) dv *= cap / length(dv);
    vec3 next = v + dv;
    vec3 next_r = sol_connection_residual(next, w, ez);
    for (int b = 0; b < 3 && !(length(next_r) < length(r)); ++b) {
      dv *= 0.5;
      next = v + dv;
      next_r = sol_connection_residual(next, w, ez);
    }
    if (!(length(next_r) < length(r))) break;
    v = next;
    r = next_r;
    scale = sol_connection_scale(w, ez, length(v));
  }
  residual = length(r) / scale;
  return v;
}

// Adds the polished vector v to the connections found (sorted by length)
// when it converged and is new; a connection found twice keeps the better
// polished copy.
void sol_add_connection(vec3 v, float residual, inout vec4 found[SOL_SEED_SLOTS], inout float residuals[SOL_SEED_SLOTS],
                        inout int count) {
  const float t = length(v);
  if (!(residual < 2e-4) || !(t > 0.0) || count == SOL_SEED_SLOTS) return;
  vec4 c = vec4(v / t, t);
  float c_residual = residual;
  int same = -1;
  for (int j = 0; j < count; ++j) {
    if (dot(found[j].xyz, c.xyz) > 1.0 - 5e-7 && abs(found[j].w - t) < 2e-4 * max(1.0, t)) same = j;
  }
  if (same >= 0) {
    if (c_residual < residuals[same]) {
      found[same] = c;
      residuals[same] = c_residual;
    }
    return;
  }
  // Insert in order of length.
  for (int j = 0; j < SOL_SEED_SLOTS; ++j) {
    if (j < count && found[j].w > c.w) {
      const vec4 held = found[j];
      const float held_residual = residuals[j];
      found[j] = c;
      residuals[j] = c_residual;
      c = held;
      c_residual = held_residual;
    }
  }
  found[count] = c;
  residuals[count] = c_residual;
  ++count;
}

// A seed for the fold partner of the connection v (0 when v is not near a
// fold): with J the Jacobian of the residual F at v, n its right singular
// vector of the smallest singular value σ (inverse iteration on JᵀJ) and
// u = J n / σ, F(v + x n)·u ≈ σ x + κ x²/2 along n (κ by central
// differences), whose other root x = -2σ/κ is where the partner lies.
vec3 sol_fold_partner(vec3 v, vec3 w) {
  const float ez = exp(w.z);
  const vec3 r = sol_connection_residual(v, w, ez);
  const float scale = max(1.0, length(v));
  const float h = 1e-3 * scale;
  mat3 J;
  J[0] = (sol_connection_residual(v + vec3(h, 0.0, 0.0), w, ez) - r) / h;
  J[1] = (sol_connection_residual(v + vec3(0.0, h, 0.0), w, ez) - r) / h;
  J[2] = (sol_connection_residual(v + vec3(0.0, 0.0, h), w, ez) - r) / h;
  const mat3 JtJ = transpose(J) * J;
  if (!(abs(determinant(JtJ)) > 1e-20)) return vec3(0.0);
  const mat3 M = inverse(JtJ);
  vec3 n = vec3(0.6, 0.5, 0.62);
  for (int i = 0; i < 4; ++i) n = normalize(M * n);
  const vec3 Jn = J * n;
  const float sigma = length(Jn);
  const float step = 0.05 * scale;
  const float kappa = dot(Jn / sigma, sol_connection_residual(v + step * n, w, ez) +
                                          sol_connection_residual(v - step * n, w, ez) - 2.0 * r) / (step * step);
  const float x = -2.0 * sigma / kappa;
  // Far from a fold the partner is either no connection or a seed of its own.
  if (!(abs(x) < 0.5 * scale) || !(abs(x) > 1e-3 * scale)) return vec3(0.0);
  return v + x * n;
}

// The connections from the origin to w (at most SOL_SEED_SLOTS), shortest
// first, as (unit direction, length), up to the shortest one found + reach;
// returns how many. None when w = 0, or when no seed converges (far outside
// the table, or at a fold where the seeds' connections vanish): the caller
// then keeps the coordinate approximation, as sol::lights_at does when the
// solver gives up.
int sol_connections(vec3 w, float reach, out vec4 found[SOL_SEED_SLOTS]) {
  for (int i = 0; i < SOL_SEED_SLOTS; ++i) found[i] = vec4(0.0);
  const vec3 target = vec3(abs(w.x), abs(w.y), w.z);
  const vec3 sign_xy = vec3(w.x < 0.0 ? -1.0 : 1.0, w.y < 0.0 ? -1.0 : 1.0, 1.0);
  if (target.x == 0.0 && target.y == 0.0) {  // the vertical line, the only connection
    if (w.z == 0.0) return 0;
    found[0] = vec4(0.0, 0.0, sign(w.z), abs(w.z));
    return 1;
  }
  const vec3 g = vec3(asinh(target.x), asinh(target.y), target.z + SOL_SEED_HEIGHT) / SOL_SEED_STEP;
  const ivec3 cell = clamp(ivec3(floor(g)), ivec3(0), ivec3(SOL_SEED_CELLS_XY - 1, SOL_SEED_CELLS_XY - 1, SOL_SEED_CELLS_Z - 1));
  const int base = ((cell.z * SOL_SEED_CELLS_XY + cell.y) * SOL_SEED_CELLS_XY + cell.x) * SOL_SEED_SLOTS;
  int count = 0;
  float residuals[SOL_SEED_SLOTS];
  for (int s = 0; s < SOL_SEED_SLOTS; ++s) {
    const vec4 seed = connection_seeds[base + s];
    if (seed.w == 0.0) break;  // slots are filled in order
    // A seed next to a connection already found would only find it again.
    const vec3 start = seed.xyz * seed.w;
    bool known = false;
    for (int j = 0; j < count; ++j) known = known || length(found[j].xyz * found[j].w - start) < SOL_SEED_SKIP * max(1.0, seed.w);
    if (known) continue;
    float residual;
    const vec3 v = sol_polish(start, target, residual);
    sol_add_connection(v, residual, found, residuals, count);
  }
  // With a reach, the longer connections: near a fold (a caustic) they come
  // in pairs that merge there, and a pair born inside a table cell has seeds
  // at none of its corners; each connection found seeds its partner.
  if (reach > 0.0) {
    const int first = count;
    vec4 originals[SOL_SEED_SLOTS] = found;  // the inserts below reorder found
    for (int j = 0; j < first; ++j) {
      if (originals[j].w > originals[0].w + reach) continue;  // beyond the reach, and its partner too
      const vec3 seed = sol_fold_partner(originals[j].xyz * originals[j].w, target);
      if (seed == vec3(0.0)) continue;
      float residual;
      const vec3 v = sol_polish(seed, target, residual);
      sol_add_connection(v, residual, found, residuals, count);
    }
  }
  int kept = 0;
  for (int i = 0; i < count; ++i) {
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
