// A quotient Γ\Sol (sol::Lattice, docs/mathematics.md): lattice
// coordinates, the fundamental domain D and the teleport back into it, the
// distance field over D (sol::QuotientField) with each cell's candidate
// images, the candidates' findings at a step of the quotient march
// (quotient_candidates, quotient_exact_step), and the positions of the
// quotient march (by Jacobi's zeta function or by Carlson's integrals,
// split between the march and resume passes). The lattice is the specialisation constants LATTICE_*
// (SOL_LATTICE_CONSTANTS): folded in as the golden constants once were.
#ifndef SOL_MARCH_QUOTIENT_GLSL
#define SOL_MARCH_QUOTIENT_GLSL

// (s, r) = [γ1 γ2]^{-1} (x, y): a point's lattice coordinates (the adjugate
// times the constant 1/det: no division per step).
vec2 lattice_coordinates(vec3 p) {
  return vec2(LATTICE_G2Y * p.x - LATTICE_G2X * p.y, LATTICE_G1X * p.y - LATTICE_G1Y * p.x) * LATTICE_INV_DET;
}

// The non-compact quotients (LATTICE_LOOPS): a z loop's D has every x, y,
// xy loops' every z (a float constant's comparison: folded once specialised).
#define LOOPS_Z_ONLY (LATTICE_LOOPS == 1.0)
#define LOOPS_XY_ONLY (LATTICE_LOOPS == 2.0)

bool in_domain(vec3 p) {
  const vec2 sr = lattice_coordinates(p);
  const bool in_xy = LOOPS_Z_ONLY || (sr.x >= 0.0 && sr.x < 1.0 && sr.y >= 0.0 && sr.y < 1.0);
  return in_xy && (LOOPS_XY_ONLY || (p.z >= 0.0 && p.z < LATTICE_HEIGHT));
}

// The point of D equivalent to p under Γ: γ3^n fixes z (scaling x by λ^n,
// y by λ^-n), then γ1, γ2 translate (x, y) into the parallelogram. With
// `step_end` (a constant at each call), p is the end of a march step from a
// point of D, less than LATTICE_HEIGHT long (every lattice's height exceeds
// kQuotientMaxStep), so n is -1, 0 or 1 and λ^{±n} a choice between
// constants (the march runs this at every step, masked: no pow there); else any n.
// `turn`: -1 where γ3^n also turned the fibre by the half-turn (a lattice of
// negative trace, n odd: then x and y change sign, and so do the first two
// frame components of a direction there), else 1 (the constant 1 for a
// lattice that does not turn, folded away).
vec3 teleport(vec3 p, const bool step_end, out float turn) {
  const float n = LOOPS_XY_ONLY ? 0.0 : -floor(p.z / LATTICE_HEIGHT);
  turn = mod(n, 2.0) != 0.0 ? LATTICE_TURN : 1.0;
  const float up = n > 0.5 ? LATTICE_LAMBDA : (n < -0.5 ? LATTICE_INV_LAMBDA : 1.0);
  const float down = n > 0.5 ? LATTICE_INV_LAMBDA : (n < -0.5 ? LATTICE_LAMBDA : 1.0);
  const float scale = step_end ? up : pow(LATTICE_SQRT_LAMBDA, 2.0 * n);
  const float inverse_scale = step_end ? down : 1.0 / scale;
  vec3 q = vec3(turn * scale * p.x, turn * p.y * inverse_scale, p.z + n * LATTICE_HEIGHT);
  if (LOOPS_XY_ONLY) q = p;
  else q.z = min(max(q.z, 0.0), LATTICE_TOP);
  if (LOOPS_Z_ONLY) return q;
  const vec2 f = floor(lattice_coordinates(q));
  const float fs = f.x, fr = f.y;
  q.x -= fs * LATTICE_G1X + fr * LATTICE_G2X;
  q.y -= fs * LATTICE_G1Y + fr * LATTICE_G2Y;
  return q;
}

// The field's cell of a point of D, as its index (sol::QuotientField::cell_of).
int field_cell(vec3 p) {
  if (LATTICE_LOOPS != 0.0) return 0;  // a non-compact quotient's cells are alike (sol::QuotientField)
  const vec3 unit = clamp(vec3(lattice_coordinates(p), p.z * LATTICE_INV_HEIGHT), 0.0, 1.0);
  const vec3 g = unit * vec3(float(kFieldCells), float(kFieldCells), float(kFieldLayers));
  const int i = min(int(g.x), kFieldCells - 1), j = min(int(g.y), kFieldCells - 1), k = min(int(g.z), kFieldLayers - 1);
  return (k * kFieldCells + j) * kFieldCells + i;
}

// The cell's candidate images (8 bits each), or kFieldAllImages.
uint field_candidates(int cell) { return field_words[2 * cell]; }

// How many of a cell's candidate slots (not kFieldAllImages) are filled:
// they fill from the lowest byte.
int field_candidate_count(uint word) {
  int n = 0;
  for (int s = 0; s < kFieldCandidates; ++s) n += ((word >> uint(8 * s)) & 255u) != uint(kFieldEmpty) ? 1 : 0;
  return n;
}

// The cell's reach (sol::QuotientField::reach): no image but its
// candidates is within it of any point of the cell.
float field_reach(int cell) { return uintBitsToFloat(field_words[2 * cell + 1]); }

// An image's kind (object code). A quotient world of one kind of object
// (specialisation constants): every image's code is that kind's, and is not
// read (on lavapipe each word a step reads at a per-lane index is a gather
// of 8 loads). The quotient's marches and shading read the kind only here.
#define SOL_KIND_COUNT(Type, code_name, code, prefix, feature, solid) +(feature_##feature ? 1 : 0)
#define SOL_KIND_ONLY(Type, code_name, code, prefix, feature, solid) feature_##feature ? code_name:
const bool ONE_KIND = (0 SOL_OBJECT_KINDS(SOL_KIND_COUNT)) == 1 && !HAS_COMPOSITES;
const int ONLY_KIND = SOL_OBJECT_KINDS(SOL_KIND_ONLY) -1;
#undef SOL_KIND_COUNT
#undef SOL_KIND_ONLY
int image_type(Image m) { return ONE_KIND ? ONLY_KIND : int(m.info.x); }

// The s-th of a cell's `listed` candidates (its word, or every image when
// `all`; field_candidate_count): its image index `i`, its record `m` and
// its object_clearances from q along u (hz: q.z's half exponentials). Past
// the listed ones (a cell listing none: the one masked pass of the
// marches' do-while over the candidates) `m` is the first record and no
// object answers (1e30).
vec3 candidate_clearances(uint word, bool all, int s, int listed, vec3 q, vec3 u, vec2 hz, out int i, out Image m) {
  i = all ? s : int((word >> uint(8 * s)) & 255u);
  m = images[s < listed ? i : 0];
  // Its bound record alone (Image::bound); a ball's centre's half
  // exponentials taken here: two exponentials cost lavapipe less than two
  // more words read (docs/history.md, "Tubes in four words").
  const vec3 dc = image_clearances(image_type(m), q, u, m, hz);
  return s < listed ? dc : vec3(1e30);
}

// One quotient march step's findings over the cell's candidates: the
// nearest (to hit) and the runner-up, the clearances ahead of the nearest
// and of the others and the least back (object_clearances), and an exact
// ball's image the ray leaves (passed) near its sphere, whose bound is
// negative on both sides there: its exact distance decides
// (quotient_exact_step, as march_exact_step's `leaving` in Sol).
struct QuotientCandidates {
  float nearest, second, clear_nearest, clear_rest, back, leaving_d;
  int nearest_i, second_i, leaving_exact;
};

// The cell's `listed` candidates (`word`, or every image where `all`) at e
// along `direction`, updating the images a shadow ray leaves (`passing`).
// Exact balls' images count by what their solves have shown at arc length
// t where that is more than their bound (`seen`, exact_seen_bound).
QuotientCandidates quotient_candidates(uint word, bool all, int listed, vec3 e, vec3 direction, vec2 hz, bool camera,
                                       float hit_epsilon, ExactSeen seen, float t, inout ivec4 passing, vec4 leave_signs) {
  QuotientCandidates c = QuotientCandidates(1e30, 1e30, 1e30, 1e30, 1e30, 1e30, -1, -1, -1);
  // (A do-while, tested at its end: see march.comp and candidate_clearances.)
  int s = 0;
  do {
    int i;
    Image m;
    const vec3 dc = candidate_clearances(word, all, s, listed, e, direction, hz, i, m);
    const bool exact_ball = HAS_EXACT_BALLS && image_type(m) == kObjectExactBall;
    const float d = exact_ball ? exact_seen_bound(seen, i, t, dc.x) : dc.x;
    const float ahead = exact_ball ? max(dc.y, d) : dc.y;  // (d may be more than the bound's clearance)
    bool leaving = false;  // an image a shadow ray leaves, until it is 2 hit_epsilon away
    if (!camera) {
      for (int p = 0; p < 4; ++p) {
        if (passing[p] == i) {
          // Until 2 hit_epsilon away, or (seen from inside) headed for a
          // face of it (sol::InsideClearances::nearest_rate; exact balls:
          // quotient_exact_step).
          const int type = image_type(m);
          const bool heads = HAS_INSIDE && inside_by_bound(type) && leave_signs[p] <= 0.0 &&
                             image_bound_clearances(type, e, direction, m, hz).x < -kHeadsDepth * hit_epsilon &&
                             image_inside_clearances(type, e, direction, m, hz, d).w < 0.0;
          // Not seen from inside, a solid drawn by its bound is passed
          // until the ray is 2 hit_epsilon out of it or into it, as in Sol
          // (passed_into, sinks_into).
          const bool into = passed_into(type, d, hit_epsilon) ||
                            (may_sink_into(type, d) && sinks_into(image_inside_clearances(type, e, direction, m, hz, -d)));
          if (d > 2.0 * hit_epsilon || heads || into) passing[p] = -1;
          else leaving = true;
        }
      }
    }
    // (Of several, the least by exact_seen_bound, so that each is solved in turn.)
    const bool held = exact_ball && leaving && d < kExactShell;
    if (held && (c.leaving_exact < 0 || d < c.leaving_d)) {
      c.leaving_exact = i;
      c.leaving_d = d;
    }
    c.back = min(c.back, held ? 1e30 : dc.z);
    if (!leaving && d < c.nearest) {
      c.second = c.nearest;
      c.second_i = c.nearest_i;
      c.nearest = d;
      c.nearest_i = i;
      c.clear_rest = min(c.clear_rest, c.clear_nearest);
      c.clear_nearest = ahead;
    } else {
      c.clear_rest = min(c.clear_rest, held ? 1e30 : ahead);
      if (!leaving && d < c.second) {
        c.second = d;
        c.second_i = i;
      }
    }
  } while (++s < listed);
  return c;
}

// One exact solve a step (each call is inlined, a Newton loop each): the
// exact ball the ray leaves (until 2 hit_epsilon away, or turned back
// towards the sphere: the passing's least step meanwhile), else the
// nearest where it is an exact ball within kExactShell (its exact
// distance, as in Sol; inside, where the solve landed, -sdf and the inside
// clearance), noted in `seen` at arc length t; a runner-up that is an
// exact ball is no hit by its bound (march_exact_step).
void quotient_exact_step(vec3 e, vec3 direction, float hit_epsilon, float t, inout QuotientCandidates c,
                         inout ExactSolve exact, inout ExactSeen seen, inout ivec4 passing, inout vec4 leave_signs) {
  const bool solve_leaving = HAS_EXACT_BALLS && c.leaving_exact >= 0;
  const bool solve_nearest = HAS_EXACT_BALLS && !solve_leaving && c.nearest_i >= 0 &&
                             image_type(images[c.nearest_i]) == kObjectExactBall && c.nearest < kExactShell;
  if (!(solve_leaving || solve_nearest)) return;
  const int ei = solve_leaving ? c.leaving_exact : c.nearest_i;
  const float sdf = exact_ball_sdf(e, images[ei].bound.xyz, images[ei].bound.w, ei, exact);
  const float slope = dot(exact.end.tangent, direction);
  const float away = exact.known ? abs(sdf) : 0.0;
  const bool inside = HAS_INSIDE && exact.known && sdf < -hit_epsilon;
  const float beyond = inside ? exact_ball_inside_clearance(away, length(exact.v), slope, hit_epsilon) : away;
  exact_seen_solved(seen, exact.known, ei, sdf, t);
  if (solve_leaving) {
    for (int p = 0; p < 4; ++p) {
      if (passing[p] != ei) continue;
      float leave_sign = leave_signs[p];
      if (exact_pass_ends(exact.known, away, slope, hit_epsilon, leave_sign)) passing[p] = -1;
      leave_signs[p] = leave_sign;
    }
    c.clear_rest = min(c.clear_rest, beyond);
    c.back = min(c.back, away);
    // (A candidate that is an exact ball, not solved at this step, is no hit.)
    if (c.nearest_i >= 0 && image_type(images[c.nearest_i]) == kObjectExactBall) c.nearest = max(c.nearest, hit_epsilon);
  } else {
    const float d = HAS_INSIDE && exact.known ? away : sdf;
    const bool stays = d <= c.second || (c.second_i >= 0 && image_type(images[c.second_i]) == kObjectExactBall);
    c.nearest_i = stays ? c.nearest_i : c.second_i;
    c.nearest = stays ? d : c.second;
    c.clear_nearest = max(c.clear_nearest, inside ? beyond : d);
  }
}

#endif  // SOL_MARCH_QUOTIENT_GLSL
