// A quotient Γ\Sol (sol::Lattice, docs/mathematics.md): lattice
// coordinates, the fundamental domain D and the teleport back into it, the
// distance field over D (sol::QuotientField) with each cell's candidate
// images, and the positions of the quotient march (by Jacobi's zeta
// function or by Carlson's integrals, split between the march and resume
// passes). The lattice is the specialisation constants LATTICE_*
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
const bool ONE_KIND = (0 SOL_OBJECT_KINDS(SOL_KIND_COUNT)) == 1;
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

#endif  // SOL_MARCH_QUOTIENT_GLSL
