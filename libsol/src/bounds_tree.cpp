#include "sol/bounds_tree.hpp"

#include <algorithm>

#include "sol/error.hpp"

namespace sol {

BoundsTree::BoundsTree(std::span<const CoordinateBox> boxes) {
  if (boxes.empty()) throw InvalidArgument("sol::BoundsTree: no boxes");
  if (boxes.size() > std::size_t{1} << 31) throw InvalidArgument("sol::BoundsTree: more than 2^31 boxes");
  m_items.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) m_items[i] = static_cast<std::uint32_t>(i);
  m_nodes.reserve(2 * (boxes.size() / kLeafSize + 1));
  build(boxes, 0, boxes.size(), 0);
}

std::uint32_t BoundsTree::build(std::span<const CoordinateBox> boxes, std::size_t begin, std::size_t end, int depth) {
  const auto index = static_cast<std::uint32_t>(m_nodes.size());
  m_nodes.emplace_back();
  CoordinateBox box, anchors;
  for (std::size_t i = begin; i < end; ++i) {
    const CoordinateBox& b = boxes[m_items[i]];
    box.add(b);
    const glm::dvec3 a = b.anchor();
    anchors.add({a, a});
  }
  m_nodes[index].box = box;
  const glm::dvec3 spread = anchors.hi - anchors.lo;
  // A leaf: few items, items that all share one anchor, or the depth's limit
  // (a median split halves the items, so it is never reached below 2^40).
  if (end - begin <= kLeafSize || (spread.x <= 0.0 && spread.y <= 0.0 && spread.z <= 0.0) || depth >= kMaxDepth) {
    m_nodes[index].first = static_cast<std::uint32_t>(begin);
    m_nodes[index].count = static_cast<std::uint32_t>(end - begin);
    return index;
  }
  const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
  const std::size_t middle = begin + (end - begin) / 2;
  std::nth_element(m_items.begin() + static_cast<std::ptrdiff_t>(begin), m_items.begin() + static_cast<std::ptrdiff_t>(middle),
                   m_items.begin() + static_cast<std::ptrdiff_t>(end), [&](std::uint32_t a, std::uint32_t b) {
                     const double pa = boxes[a].anchor()[axis], pb = boxes[b].anchor()[axis];
                     return pa < pb || (pa == pb && a < b);
                   });
  build(boxes, begin, middle, depth + 1);
  const std::uint32_t second = build(boxes, middle, end, depth + 1);
  m_nodes[index].first = second;
  m_nodes[index].count = 0;
  return index;
}

}  // namespace sol
