#pragma once
// Broad phase of contact: a uniform grid over axis-aligned boxes, built by counting sort (linear in
// the number of boxes, deterministic order). A query visits every stored item whose box overlaps the
// query box, each once: at the first of the query's cells (row by row) that the item's cells share,
// its lowest row and column in common. A query writes nothing, so threads may query one grid at once.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "krug/core/vec2.hpp"

namespace krug::contact {

struct Box {
  Vec2 min{1e300, 1e300};
  Vec2 max{-1e300, -1e300};

  void include(Vec2 p) {
    min = {std::min(min.x, p.x), std::min(min.y, p.y)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y)};
  }
  Box expanded(double margin) const { return {{min.x - margin, min.y - margin}, {max.x + margin, max.y + margin}}; }
  bool overlaps(const Box& o) const {
    return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y;
  }
};

class UniformGrid {
 public:
  // Stores items 0..boxes.size()-1. The cell size defaults to the mean box extent, which keeps the
  // items per cell bounded for meshes of similar zone sizes; the cell count is capped at 4 x items.
  void build(const std::vector<Box>& boxes, double cell_size = 0.0) {
    boxes_ = &boxes;
    const std::size_t n = boxes.size();
    cell_start_.clear();
    items_.clear();
    first_cell_.resize(n);
    if (n == 0) return;
    bounds_ = Box{};
    double extent_sum = 0.0;
    for (const Box& b : boxes) {
      bounds_.include(b.min);
      bounds_.include(b.max);
      extent_sum += std::max(b.max.x - b.min.x, b.max.y - b.min.y);
    }
    double cell = cell_size > 0.0 ? cell_size : extent_sum / static_cast<double>(n);
    const double width = std::max(bounds_.max.x - bounds_.min.x, 1e-300);
    const double height = std::max(bounds_.max.y - bounds_.min.y, 1e-300);
    const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
    if (!(cell > 0.0)) cell = std::max(width, height);
    if ((width / cell + 1.0) * (height / cell + 1.0) > max_cells) cell = std::sqrt(width * height / max_cells) * 1.01;
    inverse_cell_ = 1.0 / cell;
    nx_ = static_cast<int>(width * inverse_cell_) + 1;
    ny_ = static_cast<int>(height * inverse_cell_) + 1;
    cell_start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) visit_cells(boxes[i], [&](std::size_t c, int, int) { ++cell_start_[c + 1]; });
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    items_.resize(cell_start_.back());
    std::vector<std::uint32_t>& fill = fill_;
    fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      visit_cells(boxes[i], [&](std::size_t c, int, int) { items_[fill[c]++] = static_cast<std::uint32_t>(i); });
      first_cell_[i] = {cell_index(boxes[i].min.x - bounds_.min.x, nx_),
                        cell_index(boxes[i].min.y - bounds_.min.y, ny_)};
    }
  }

  // Calls visit(item) once for every item whose box overlaps `query`.
  template <class Visit>
  void query(const Box& query, Visit&& visit) const {
    if (items_.empty() || !bounds_.overlaps(query)) return;  // every stored box lies within bounds_
    const int i0 = cell_index(query.min.x - bounds_.min.x, nx_), j0 = cell_index(query.min.y - bounds_.min.y, ny_);
    visit_cells(query, [&](std::size_t c, int i, int j) {
      for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const std::uint32_t item = items_[k];
        const FirstCell first = first_cell_[item];
        // Not the first cell the item and the query share: visited there.
        if (i != std::max(i0, first.i) || j != std::max(j0, first.j)) continue;
        if ((*boxes_)[item].overlaps(query)) visit(static_cast<std::size_t>(item));
      }
    });
  }

 private:
  // Calls visit(cell, column, row) for the cells the box covers, row by row.
  template <class Visit>
  void visit_cells(const Box& b, Visit&& visit) const {
    const int i0 = cell_index(b.min.x - bounds_.min.x, nx_), i1 = cell_index(b.max.x - bounds_.min.x, nx_);
    const int j0 = cell_index(b.min.y - bounds_.min.y, ny_), j1 = cell_index(b.max.y - bounds_.min.y, ny_);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        visit(static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i), i, j);
      }
    }
  }
  int cell_index(double offset, int count) const {
    const double c = std::floor(offset * inverse_cell_);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(count - 1)));
  }

  const std::vector<Box>* boxes_ = nullptr;
  Box bounds_;
  double inverse_cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> items_;
  std::vector<std::uint32_t> fill_;  // build's scratch: the next free slot of each cell
  struct FirstCell {
    int i = 0, j = 0;  // the lowest column and row of an item's cells
  };
  std::vector<FirstCell> first_cell_;
};

}  // namespace krug::contact
