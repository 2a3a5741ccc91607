#include "sol/quotient_field.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include <glm/common.hpp>

#include "sol/distance.hpp"
#include "sol/lattice.hpp"

namespace sol {
namespace {

constexpr int kN = QuotientField::kCells, kNz = QuotientField::kLayers;
constexpr std::size_t kCellCount = static_cast<std::size_t>(kNz) * kN * kN;
// Float rounding of the position and the lattice coordinates in the
// kernel, far below this.
constexpr double kRounding = kernel::kFieldRounding;

std::size_t cell_index(int i, int j, int k) {
  return (static_cast<std::size_t>(k) * kN + static_cast<std::size_t>(j)) * kN + static_cast<std::size_t>(i);
}

// The point of D's closure at lattice coordinates (s, r) and height z.
glm::dvec3 point_at(const Lattice& lattice, double s, double r, double z) {
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  return {s * g1.x + r * g2.x, s * g1.y + r * g2.y, z};
}

// The bound b_i the march steps by (balls, exact or not, by their bound:
// the sphere drawn lies within it).
double bound(const MarchObject& image, const glm::dvec3& q) {
  if (const Ball* ball = std::get_if<Ball>(&image.shape)) return sdf_ball(q, ball->center, ball->radius);
  return object_distance(image, q);
}

// Runs f(k) for k in [0, count) on the hardware's threads.
template <class F>
void parallel_for(int count, F&& f) {
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 8u));
  std::vector<std::jthread> pool;
  for (unsigned t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      for (int k = static_cast<int>(t); k < count; k += static_cast<int>(threads)) f(k);
    });
  }
}

}  // namespace

QuotientField::QuotientField(const std::vector<MarchObject>& images, double max_step, const Lattice& lattice)
    : m_lattice(lattice), m_image_count(images.size()), m_max_step(max_step) {
  if (images.size() > kMaxImages) {
    throw std::invalid_argument("sol::QuotientField: at most " + std::to_string(kMaxImages) + " images, got " +
                                std::to_string(images.size()));
  }
  if (!(max_step > 0.0 && max_step <= kQuotientMaxStep)) {
    throw std::invalid_argument("sol::QuotientField: max_step must be in (0, kQuotientMaxStep]");
  }
  m_words.assign(2 * kCellCount, 0u);
  if (!lattice.compact()) {
    // A non-compact quotient's D is unbounded (in x, y or in z): no grid
    // over it. Every cell (and cell_of: the first) lists every image, and
    // the reach is the longest step.
    float f = static_cast<float>(max_step - kRounding);
    if (static_cast<double>(f) > max_step - kRounding) f = std::nextafter(f, -1.0f);
    for (std::size_t c = 0; c < kCellCount; ++c) {
      m_words[2 * c] = kernel::kFieldAllImages;
      m_words[2 * c + 1] = std::bit_cast<std::uint32_t>(f);
    }
    return;
  }
  const double h = lattice.height();
  // Per layer, the cells' diameter (at most, over the layer's heights).
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  const double dz = h / kNz;
  std::vector<double> diameter(kNz);
  for (int k = 0; k < kNz; ++k) {
    const double lo = std::exp(-2.0 * k * dz), hi = std::exp(2.0 * (k + 1) * dz);  // e^{-2 z0}, e^{2 z1}
    const double dx = (std::abs(g1.x) + std::abs(g2.x)) / kN, dy = (std::abs(g1.y) + std::abs(g2.y)) / kN;
    diameter[static_cast<std::size_t>(k)] = std::sqrt(lo * dx * dx + hi * dy * dy + dz * dz);
  }
  parallel_for(kNz, [&](int k) {
    const double radius = 0.5 * diameter[static_cast<std::size_t>(k)];
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) {
        const glm::dvec3 centre = point_at(lattice, (i + 0.5) / kN, (j + 0.5) / kN, (k + 0.5) * dz);
        std::uint32_t word = 0xFFFFFFFFu;  // every slot empty (kFieldEmpty)
        // The candidates: every image whose bound can be below kNear in the
        // cell, and at least the nearest one (a ray far from every surface
        // then steps by its clearance, up to the next image's bound); more than
        // kCandidates: every image. The reach: the least bound of the other
        // images over the cell, capped at the longest step.
        int count = 0;
        // The least and second least bound over the cell of the images that
        // are not within kNear, and the image of the least.
        double first = std::numeric_limits<double>::infinity(), second = first;
        std::size_t first_image = 0;
        for (std::size_t m = 0; m < images.size(); ++m) {
          const double least = bound(images[m], centre) - radius;
          if (least > kNear) {
            if (least < first) {
              second = first;
              first = least;
              first_image = m;
            } else {
              second = std::min(second, least);
            }
            continue;
          }
          if (count == kCandidates) {
            word = kernel::kFieldAllImages;
            break;
          }
          word &= ~(0xFFu << (8 * count));
          word |= static_cast<std::uint32_t>(m) << (8 * count);
          ++count;
        }
        double reach = std::min(max_step, first);
        if (word == kernel::kFieldAllImages) {
          reach = max_step;  // every image is evaluated
        } else if (count == 0 && !images.empty()) {
          word = (word & ~0xFFu) | static_cast<std::uint32_t>(first_image);  // only the nearest
          reach = std::min(max_step, second);
        }
        m_words[2 * cell_index(i, j, k)] = word;
        // Rounded down to float, less the kernel's rounding: never above the bounds.
        float f = static_cast<float>(reach - kRounding);
        if (static_cast<double>(f) > reach - kRounding) f = std::nextafter(f, -1.0f);
        m_words[2 * cell_index(i, j, k) + 1] = std::bit_cast<std::uint32_t>(f);
      }
    }
  });
}

QuotientField::Cell QuotientField::cell_of(const glm::dvec3& q) const {
  const Lattice& lattice = m_lattice;
  if (!lattice.compact()) return {0, 0, 0};  // every cell alike (the constructor)
  const glm::dvec2 sr = lattice.lattice_coordinates(q.x, q.y);
  const glm::dvec3 g(std::clamp(sr.x, 0.0, 1.0) * kN, std::clamp(sr.y, 0.0, 1.0) * kN,
                     std::clamp(q.z / lattice.height(), 0.0, 1.0) * kNz);
  const int i = std::min(static_cast<int>(g.x), kN - 1), j = std::min(static_cast<int>(g.y), kN - 1),
            k = std::min(static_cast<int>(g.z), kNz - 1);
  return {i, j, k};
}

std::uint32_t QuotientField::cell_candidates(int i, int j, int k) const {
  return m_words[2 * cell_index(i, j, k)];
}

double QuotientField::reach(const Cell& c) const {
  return std::bit_cast<float>(m_words[2 * cell_index(c.i, c.j, c.k) + 1]);
}

void QuotientField::candidates(const Cell& c, std::vector<int>& out) const {
  out.clear();
  const std::uint32_t word = cell_candidates(c.i, c.j, c.k);
  if (word == kernel::kFieldAllImages) {
    for (std::size_t m = 0; m < m_image_count; ++m) out.push_back(static_cast<int>(m));
    return;
  }
  for (int s = 0; s < kCandidates; ++s) {
    const int m = static_cast<int>((word >> (8 * s)) & 0xFFu);
    if (m != kernel::kFieldEmpty) out.push_back(m);
  }
}

double QuotientField::reach(const glm::dvec3& q) const { return reach(cell_of(q)); }

std::vector<int> QuotientField::candidates(const glm::dvec3& q) const {
  std::vector<int> out;
  candidates(cell_of(q), out);
  return out;
}

void QuotientField::sample(const glm::dvec3& q, Sample& out) const {
  const Cell c = cell_of(q);
  out.reach = reach(c);
  candidates(c, out.candidates);
}

}  // namespace sol
