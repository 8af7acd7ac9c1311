// Copyright (C) 2025 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Axis-aligned bounding box tree over a set of boxes with a pruned,
// nearest-child-first search for the closest object to a point.

#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace tribofx::geometry
{

/// Bounding box tree over boxes stored as [lo_0..lo_{g-1}, hi_0..hi_{g-1}].
template <int gdim>
class BoxTree
{
public:
  using Box = std::array<double, 2 * gdim>;

  /// Relative slack on box distances when pruning, so that objects whose
  /// distance may tie with the current minimum are never skipped.
  static constexpr double prune_rtol = 1e-10;

  /// Maximum number of objects in a leaf.
  static constexpr std::int32_t leaf_size = 4;

  /// Capacity of the traversal stack of nearest_search.
  static constexpr std::size_t max_stack = 256;

  explicit BoxTree(std::span<const double> boxes)
      : _num_objects(boxes.size() / (2 * gdim))
  {
    _boxes.resize(_num_objects);
    for (std::size_t i = 0; i < _num_objects; ++i)
      std::copy_n(boxes.data() + i * 2 * gdim, 2 * gdim, _boxes[i].begin());
    _order.resize(_num_objects);
    std::iota(_order.begin(), _order.end(), 0);
    std::vector<std::array<double, gdim>> centres(_num_objects);
    for (std::size_t i = 0; i < _num_objects; ++i)
      for (int c = 0; c < gdim; ++c)
        centres[i][c] = 0.5 * (_boxes[i][c] + _boxes[i][gdim + c]);
    if (_num_objects > 0)
      build(0, static_cast<std::int32_t>(_num_objects), centres);
  }

  /// Squared distance from x to a box (zero inside).
  static double distance2(const double* x, const Box& b)
  {
    double d2 = 0.0;
    for (int c = 0; c < gdim; ++c)
    {
      const double r = std::max(std::max(b[c] - x[c], x[c] - b[gdim + c]), 0.0);
      d2 += r * r;
    }
    return d2;
  }

  /// Call visit(i) for every object whose box could hold a point within the
  /// current best distance dmin (updated by visit), nearest subtrees first.
  template <typename Visitor>
  void nearest_search(const double* x, const double& dmin, Visitor&& visit) const
  {
    if (_nodes.empty())
      return;
    constexpr double c = (1.0 - prune_rtol) * (1.0 - prune_rtol);
    auto pruned = [&dmin](double d2) { return d2 * c > dmin * dmin; };
    // Depth-first with the nearer child on top: the stack holds at most one
    // entry per level plus one, so a fixed array (no allocation per query) does
    // for any tree this size can build (depth <= 2 log2(objects)).
    std::array<std::pair<std::int32_t, double>, max_stack> stack;
    std::size_t top = 0;
    stack[top++] = {0, distance2(x, _nodes[0].box)};
    while (top > 0)
    {
      const auto [id, d2] = stack[--top];
      if (pruned(d2))
        continue;
      const Node& node = _nodes[id];
      if (node.child[0] < 0)
      {
        for (std::int32_t k = node.begin; k < node.end; ++k)
        {
          const std::int32_t obj = _order[k];
          if (!pruned(distance2(x, _boxes[obj])))
            visit(obj);
        }
      }
      else
      {
        const double d0 = distance2(x, _nodes[node.child[0]].box);
        const double d1 = distance2(x, _nodes[node.child[1]].box);
        // Push the farther child first so the nearer one is searched first
        if (top + 2 > max_stack)
          throw std::runtime_error("box tree deeper than the search stack");
        if (d0 <= d1)
        {
          stack[top++] = {node.child[1], d1};
          stack[top++] = {node.child[0], d0};
        }
        else
        {
          stack[top++] = {node.child[0], d0};
          stack[top++] = {node.child[1], d1};
        }
      }
    }
  }

  std::size_t num_nodes() const { return _nodes.size(); }

  /// New boxes of the same objects: the node boxes are recomputed bottom-up and
  /// the tree topology is kept (children are stored after their parent).
  void refit(std::span<const double> boxes)
  {
    if (boxes.size() != _num_objects * 2 * gdim)
      throw std::invalid_argument("refit: the number of boxes changed");
    for (std::size_t i = 0; i < _num_objects; ++i)
      std::copy_n(boxes.data() + i * 2 * gdim, 2 * gdim, _boxes[i].begin());
    for (auto id = static_cast<std::int64_t>(_nodes.size()) - 1; id >= 0; --id)
    {
      Node& node = _nodes[id];
      auto merge = [&node](const Box& b)
      {
        for (int c = 0; c < gdim; ++c)
        {
          node.box[c] = std::min(node.box[c], b[c]);
          node.box[gdim + c] = std::max(node.box[gdim + c], b[gdim + c]);
        }
      };
      if (node.child[0] < 0)
      {
        node.box = _boxes[_order[node.begin]];
        for (std::int32_t k = node.begin + 1; k < node.end; ++k)
          merge(_boxes[_order[k]]);
      }
      else
      {
        node.box = _nodes[node.child[0]].box;
        merge(_nodes[node.child[1]].box);
      }
    }
  }

private:
  struct Node
  {
    Box box;
    std::array<std::int32_t, 2> child;
    std::int32_t begin, end;
  };

  // Build the subtree over _order[begin:end), splitting at the median of the
  // box centres along the longest extent of the centres; returns node index.
  std::int32_t build(std::int32_t begin, std::int32_t end,
                     const std::vector<std::array<double, gdim>>& centres)
  {
    const auto id = static_cast<std::int32_t>(_nodes.size());
    _nodes.push_back(Node{_boxes[_order[begin]], {-1, -1}, begin, end});
    Box box = _boxes[_order[begin]];
    std::array<double, gdim> clo = centres[_order[begin]], chi = clo;
    for (std::int32_t k = begin + 1; k < end; ++k)
    {
      const Box& b = _boxes[_order[k]];
      for (int c = 0; c < gdim; ++c)
      {
        box[c] = std::min(box[c], b[c]);
        box[gdim + c] = std::max(box[gdim + c], b[gdim + c]);
        clo[c] = std::min(clo[c], centres[_order[k]][c]);
        chi[c] = std::max(chi[c], centres[_order[k]][c]);
      }
    }
    _nodes[id].box = box;
    if (end - begin <= leaf_size)
      return id;

    int axis = 0;
    for (int c = 1; c < gdim; ++c)
      if (chi[c] - clo[c] > chi[axis] - clo[axis])
        axis = c;
    const std::int32_t mid = begin + (end - begin) / 2;
    std::nth_element(_order.begin() + begin, _order.begin() + mid, _order.begin() + end,
                     [&centres, axis](std::int32_t a, std::int32_t b)
                     { return centres[a][axis] < centres[b][axis]; });
    const std::int32_t c0 = build(begin, mid, centres);
    const std::int32_t c1 = build(mid, end, centres);
    _nodes[id].child = {c0, c1};
    return id;
  }

  std::size_t _num_objects;
  std::vector<Box> _boxes;
  std::vector<std::int32_t> _order;
  std::vector<Node> _nodes;
};

} // namespace tribofx::geometry
