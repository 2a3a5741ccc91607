// A distance field of a quotient world over the fundamental domain D, built
// once per world for the kernels: one read per march step instead of the
// distance bounds of every image around D.
//
// B(q) = min(S, min_i b_i(q)) is what a step of the quotient march may be
// (b_i the distance bound of the i-th image of sol::quotient_images, which
// lists every image a step of at most S, the world's longest step
// sol::quotient_max_step, can reach from D). The field samples B at the nodes of a
// grid over D in the coordinates (s, r, z/h), (x, y) = s γ1 + r γ2, and
// reads it back at the node n nearest to q, at fractional offsets
// (δ_s, δ_r, δ_z) <= 1/2 of a cell from q, as
//   F(q) = B(n) - (δ_s L_s + δ_r L_r + δ_z L_z) - ε,
// where L_s, L_r bound the Sol lengths of the cell edges of q's layer (along
// s the coordinates move by γ1/kCells at heights in [z0, z1], so
// L_s = sqrt(e^{-2 z0} γ1x² + e^{2 z1} γ1y²)/kCells; likewise L_r with γ2),
// L_z = h/kLayers, and ε covers the kernel's float rounding. Why it never
// overestimates: b_i, hence B, is 1-Lipschitz in the Sol distance (a
// distance to a set, or a maximum of distances in hyperbolic planes onto
// which Sol projects without stretching), so B(q) >= B(n) - d(q, n), and
// d(q, n) is at most the length of the path from q along s, then r (both at
// q's height), then z to n. One read per step; on average 0.027 below B
// (trilinear interpolation with the matching bound is 0.036 below, for 8 reads).
//
// Each cell lists its candidate images, which the march evaluates at every
// step in the cell: every image whose bound can fall below kFieldNear
// somewhere in the cell (b_i(centre) - the cell's circumradius <=
// kFieldNear), and where there is none the image nearest to the cell (the
// least b_i(centre)). For q in the cell every other image has b_i(q) >
// kFieldNear, so the candidate that reaches hit_epsilon is the object hit.
// Each cell also keeps its reach R, the least of b_j(centre) -
// circumradius over the images that are not candidates (so R > kFieldNear),
// at most S (S where every image is a candidate), less ε: a step of at most
// R from q reaches none of them, so the march may step
// max(F, min(the candidates' least clearance, R)) (sol/clearance.hpp). The
// nearest image as a candidate far from surfaces lets a ray that passes it
// step by its clearance up to the next image's bound: about 30 % fewer
// steps in lattice-balls than steps by F there (docs/renderer.md).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"
#include "sol/march.hpp"

namespace sol {

class QuotientField {
 public:
  static constexpr int kCells = kernel::kFieldCells;
  static constexpr int kLayers = kernel::kFieldLayers;
  static constexpr double kNear = kernel::kFieldNear;
  static constexpr int kCandidates = kernel::kFieldCandidates;

  /// Samples B over D for `images` (sol::quotient_images of a quotient
  /// world for the longest step `max_step`, at most 254 of them;
  /// std::invalid_argument beyond, or for a step outside (0,
  /// kQuotientMaxStep]). About 150 000 nodes times the images' bounds.
  QuotientField(const std::vector<MarchObject>& images, double max_step);

  /// F(q) for q in D (clamped into it), as the kernel computes it, in double.
  double lower_bound(const glm::dvec3& q) const;
  /// The reach of q's cell: no image but its candidates is within it of
  /// any point of the cell; in (kNear, max_step()].
  double reach(const glm::dvec3& q) const;
  /// The candidate images of q's cell (indices into the images; never none
  /// while there are images), or every image when the cell has more than
  /// kCandidates.
  std::vector<int> candidates(const glm::dvec3& q) const;
  /// All three for q's cell from one lookup, the candidates into a vector
  /// the caller keeps (a march takes one a step: no allocation per step).
  struct Sample {
    double lower_bound = 0.0, reach = 0.0;
    std::vector<int> candidates;
  };
  void sample(const glm::dvec3& q, Sample& out) const;
  /// The longest step: B's cap, and the reach's.
  double max_step() const { return m_max_step; }

  /// The kernel's buffer: per layer L_s and L_r (2 kLayers floats), the node
  /// values ((kLayers + 1)(kCells + 1)² floats, index (k (kCells + 1) + j)(kCells + 1) + i
  /// for s_i, r_j, z_k), the cells' candidates (kLayers kCells² words,
  /// 8 bits a candidate, index (k kCells + j) kCells + i) and the cells'
  /// reaches (kLayers kCells² floats, the same index), all as 32-bit words
  /// (floats by their bits).
  const std::vector<std::uint32_t>& words() const { return m_words; }

 private:
  struct Cell {
    int i, j, k;
    glm::dvec3 f;  // fractions within the cell
  };
  Cell cell_of(const glm::dvec3& q) const;
  double lower_bound(const Cell& c) const;
  double reach(const Cell& c) const;
  void candidates(const Cell& c, std::vector<int>& out) const;  // replaces out's contents
  float edge(int layer, int axis) const;
  float node(int i, int j, int k) const;
  std::uint32_t cell_candidates(int i, int j, int k) const;

  std::vector<std::uint32_t> m_words;
  std::size_t m_image_count = 0;
  double m_max_step = kQuotientMaxStep;
};

}  // namespace sol
