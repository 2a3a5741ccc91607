// A tree of bounds over a world's objects: a bounding volume hierarchy
// whose nodes are coordinate boxes (sol/coordinate_box.hpp), built once per
// world in double. The march asks it, at each step, for the objects that
// can be nearer than the nearest it has found: a node whose box's distance
// bound (sol::box_distance_lower_bound, a lower bound of the Sol distance
// to everything inside it) is not below that is skipped with all it holds,
// so a step visits about the logarithm of the number of objects.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/coordinate_box.hpp"
#include "sol/kernel_constants.h"

namespace sol {

class BoundsTree {
 public:
  /// A node, in depth-first order: an inner node's first child is the next
  /// node, its second `first`; a leaf holds items()[first, first + count).
  struct Node {
    CoordinateBox box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;  ///< 0 for an inner node
  };
  /// The most items a leaf holds.
  static constexpr std::size_t kLeafSize = 4;
  /// The deepest a tree grows (a median split halves the items: 2^40 of them).
  static constexpr int kMaxDepth = kernel::kTreeMaxDepth;

  /// The tree over `boxes` (item i is boxes[i]; at least one box). Each
  /// node splits its items at the median of their boxes' anchors
  /// (CoordinateBox::anchor) along the axis where they spread most.
  explicit BoundsTree(std::span<const CoordinateBox> boxes);

  const std::vector<Node>& nodes() const { return m_nodes; }
  /// The items in leaf order.
  const std::vector<std::uint32_t>& items() const { return m_items; }

  /// Visits every item whose box's distance bound from q is below the
  /// limit, nearer nodes first: `visit(item)` returns the limit from then
  /// on (the nearest distance found, say), so that what cannot be nearer
  /// is skipped. The limit only needs to be an upper bound of what the
  /// caller still wants; items at or beyond it may or may not be visited.
  template <class Visit>
  void search(const glm::dvec3& q, double limit, Visit&& visit) const {
    search(q, limit, visit, [](double) { return -1.0; });
  }

  /// The same, where a node below the limit may also be taken whole:
  /// `cover(bound)`, asked before a node is opened, returns the limit from
  /// then on where the caller takes the node's bound for all it holds
  /// (without visiting them), or a negative number to open it.
  template <class Visit, class Cover>
  void search(const glm::dvec3& q, double limit, Visit&& visit, Cover&& cover) const {
    struct Pending {
      std::uint32_t node;
      double bound;
    };
    Pending stack[kMaxDepth + 2];
    int top = 0;
    const glm::dvec2 e(std::exp(-q.z), std::exp(q.z));  // (box_distance_lower_bound's, once)
    stack[top++] = {0, box_distance_lower_bound(m_nodes[0].box, q, e)};
    while (top > 0) {
      const Pending p = stack[--top];
      if (!(p.bound < limit)) continue;
      if (const double covered = cover(p.bound); covered >= 0.0) {
        limit = covered;
        continue;
      }
      const Node& n = m_nodes[p.node];
      if (n.count > 0) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) limit = visit(m_items[i]);
        continue;
      }
      const std::uint32_t a = p.node + 1, b = n.first;
      const double da = box_distance_lower_bound(m_nodes[a].box, q, e), db = box_distance_lower_bound(m_nodes[b].box, q, e);
      // The nearer child on top, visited first.
      if (da <= db) {
        if (db < limit) stack[top++] = {b, db};
        if (da < limit) stack[top++] = {a, da};
      } else {
        if (da < limit) stack[top++] = {a, da};
        if (db < limit) stack[top++] = {b, db};
      }
    }
  }

 private:
  std::uint32_t build(std::span<const CoordinateBox> boxes, std::size_t begin, std::size_t end, int depth);

  std::vector<Node> m_nodes;
  std::vector<std::uint32_t> m_items;
};

}  // namespace sol
