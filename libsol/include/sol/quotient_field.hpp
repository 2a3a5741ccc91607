// The field of a quotient world over the fundamental domain D, built once
// per world for the kernels: one read per march step (a cell's candidate
// images and its reach) instead of the distance bounds of every image
// around D.
//
// Let b_i be the distance bound of the i-th image of sol::quotient_images,
// which lists every image a step of at most S, the world's longest step
// sol::quotient_max_step, can reach from D. D is cut into cells of a grid in
// the coordinates (s, r, z/h), (x, y) = s γ1 + r γ2. Each cell lists its
// candidate images, which the march evaluates at every step in the cell:
// every image whose bound can fall below kFieldNear somewhere in the cell
// (b_i(centre) - the cell's circumradius <= kFieldNear), and where there
// is none the image nearest to the cell (the least b_i(centre)). For q in
// the cell every other image has b_i(q) > kFieldNear, so the candidate
// that reaches hit_epsilon is the object hit. Each cell also keeps its
// reach R, the least of b_j(centre) - circumradius over the images that
// are not candidates (so R > kFieldNear), at most S (S where every image is
// a candidate), less ε for the kernel's float rounding: b_j is 1-Lipschitz
// in the Sol distance (a distance to a set, or a maximum of distances in
// hyperbolic planes onto which Sol projects without stretching), so a step
// of at most R from any point of the cell reaches none of them, and the
// march may step min(the candidates' least clearance, R) (sol/clearance.hpp).
// The nearest image as a candidate far from surfaces lets a ray that passes
// it step by its clearance up to the next image's bound. (A sampled lower
// bound of every image's at the grid's nodes was tried and dropped:
// docs/history.md, "The quotient field's sampled bound, dropped".) The
// cells scan every image: every listed image lies within the longest step
// of D, and a cell needs each image's bound up to that step, so a tree of
// bounds over them leaves out too few to pay (docs/history.md).
//
// A non-compact quotient (Lattice::Loops: a z loop, xy loops) has an
// unbounded D and few images near it: every cell lists every image, with
// the longest step as its reach (the march as in Sol, over the images).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"
#include "sol/march.hpp"

namespace sol {

class QuotientField {
 public:
  static constexpr int kCells = kernel::kFieldCells;
  static constexpr int kLayers = kernel::kFieldLayers;
  static constexpr double kNear = kernel::kFieldNear;
  static constexpr int kCandidates = kernel::kFieldCandidates;
  /// The most images a field takes (a cell's candidates are bytes, two of
  /// whose values mark an empty slot and every image): the CPU renderer's
  /// limit on a quotient world.
  static constexpr std::size_t kMaxImages = kernel::kMaxQuotientImages;

  /// The cells of the field for `images` (sol::quotient_images of a
  /// quotient world for the longest step `max_step`, at most kMaxImages of them;
  /// std::invalid_argument beyond, or for a step outside (0,
  /// kQuotientMaxStep]), over the fundamental domain of `lattice` (the
  /// world's, World::lattice). About 131 000 cells times the images' bounds.
  QuotientField(const std::vector<MarchObject>& images, double max_step, const Lattice& lattice);

  /// The reach of q's cell: no image but its candidates is within it of
  /// any point of the cell; in (kNear, max_step()].
  double reach(const glm::dvec3& q) const;
  /// The candidate images of q's cell (indices into the images; never none
  /// while there are images), or every image when the cell has more than
  /// kCandidates.
  std::vector<int> candidates(const glm::dvec3& q) const;
  /// Both for q's cell from one lookup, the candidates into a vector the
  /// caller keeps (a march takes one a step: no allocation per step).
  struct Sample {
    double reach = 0.0;
    std::vector<int> candidates;
  };
  void sample(const glm::dvec3& q, Sample& out) const;
  /// The longest step: the reach's cap.
  double max_step() const { return m_max_step; }

  /// The kernel's buffer: per cell (index (k kCells + j) kCells + i for the
  /// cell at s_i, r_j, z_k) two 32-bit words, its candidates (8 bits a
  /// candidate) and its reach (a float by its bits).
  const std::vector<std::uint32_t>& words() const { return m_words; }

 private:
  struct Cell {
    int i, j, k;
  };
  Cell cell_of(const glm::dvec3& q) const;
  double reach(const Cell& c) const;
  void candidates(const Cell& c, std::vector<int>& out) const;  // replaces out's contents
  std::uint32_t cell_candidates(int i, int j, int k) const;

  Lattice m_lattice;
  std::vector<std::uint32_t> m_words;
  std::size_t m_image_count = 0;
  double m_max_step = kQuotientMaxStep;
};

}  // namespace sol
