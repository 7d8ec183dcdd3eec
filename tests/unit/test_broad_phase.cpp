// Broad phase of contact (krug/contact/broad_phase.hpp): the uniform grid against a brute-force
// overlap check. The header promises that a query "calls visit(item) once for every item whose box
// overlaps `query`" (Box::overlaps, closed intervals): exactly the overlapping items, each once, not
// a conservative superset. Asserted for seeded random boxes at several cell sizes, for queries
// outside the stored bounds, and for touching and degenerate (point) boxes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

#include "krug/contact/broad_phase.hpp"

using namespace krug;
using namespace krug::contact;

namespace {

// Uniform in [low, high) from the raw 32-bit output of std::mt19937, which the standard fixes
// bit for bit (std::uniform_real_distribution does not: another library would draw other boxes).
double uniform(std::mt19937& rng, double low, double high) {
  return low + (high - low) * (static_cast<double>(rng()) / 4294967296.0);
}

// `count` boxes with corners uniform in [0, 10]^2 and extents uniform in [0, max_extent] each way.
std::vector<Box> random_boxes(std::mt19937& rng, int count, double max_extent) {
  std::vector<Box> boxes;
  for (int k = 0; k < count; ++k) {
    const double x = uniform(rng, 0.0, 10.0), y = uniform(rng, 0.0, 10.0);
    const double w = uniform(rng, 0.0, max_extent), h = uniform(rng, 0.0, max_extent);
    boxes.push_back({{x, y}, {x + w, y + h}});
  }
  return boxes;
}

// Items reported by the grid, in the order visited, and the brute-force answer (sorted).
std::vector<std::size_t> grid_answer(const UniformGrid& grid, const Box& query) {
  std::vector<std::size_t> found;
  grid.query(query, [&](std::size_t item) { found.push_back(item); });
  return found;
}

std::vector<std::size_t> brute_force(const std::vector<Box>& boxes, const Box& query) {
  std::vector<std::size_t> expected;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].overlaps(query)) expected.push_back(k);
  }
  return expected;
}

// Exactly the overlapping items, each reported once.
void check_query(const UniformGrid& grid, const std::vector<Box>& boxes, const Box& query) {
  std::vector<std::size_t> found = grid_answer(grid, query);
  const std::size_t reported = found.size();
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  CHECK(found.size() == reported);  // no item twice
  CHECK(found == brute_force(boxes, query));
}

}  // namespace

TEST_CASE("Box: include, expanded and closed-interval overlap", "[kernels][broad_phase]") {
  Box box;  // empty: min = +1e300, max = -1e300 overlaps nothing
  CHECK_FALSE(box.overlaps({{0.0, 0.0}, {1.0, 1.0}}));
  box.include({1.0, 2.0});
  box.include({-1.0, 3.0});
  CHECK(box.min.x == -1.0);
  CHECK(box.min.y == 2.0);
  CHECK(box.max.x == 1.0);
  CHECK(box.max.y == 3.0);
  const Box grown = box.expanded(0.5);  // [-1.5, 1.5] x [1.5, 3.5]
  CHECK(grown.min.x == -1.5);
  CHECK(grown.min.y == 1.5);
  CHECK(grown.max.x == 1.5);
  CHECK(grown.max.y == 3.5);
  // Touching edges and corners count (<=): [1, 2] x [3, 4] shares the corner (1, 3) with box.
  CHECK(box.overlaps({{1.0, 3.0}, {2.0, 4.0}}));
  CHECK_FALSE(box.overlaps({{1.0 + 1e-12, 3.0}, {2.0, 4.0}}));
}

TEST_CASE("UniformGrid: every overlapping box reported once, and only those", "[kernels][broad_phase]") {
  std::mt19937 rng(20240611u);  // fixed seed: the same boxes on every run
  // Cell sizes: the default (mean extent), finer than most boxes, coarser than the whole domain.
  const double cell_size = GENERATE(0.0, 0.15, 20.0);
  const double max_extent = GENERATE(0.5, 3.0);
  const std::vector<Box> boxes = random_boxes(rng, 48, max_extent);
  UniformGrid grid;
  grid.build(boxes, cell_size);
  INFO("cell size " << cell_size << ", max extent " << max_extent);

  // Every stored box queried against the others: the pairs found equal the brute-force pairs.
  long pairs_found = 0, pairs_expected = 0;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    check_query(grid, boxes, boxes[k]);
    pairs_found += static_cast<long>(grid_answer(grid, boxes[k]).size());
    pairs_expected += static_cast<long>(brute_force(boxes, boxes[k]).size());
  }
  CHECK(pairs_found == pairs_expected);
  // The sample has real overlaps, not only each box with itself (48 boxes of mean extent 0.25 or 1.5
  // in a 10 x 10 square: 1128 pairs, each overlapping with probability ~(2 x extent / 10)^2, so a few
  // or some tens of overlapping pairs).
  CHECK(pairs_expected > static_cast<long>(boxes.size()));

  // Random query boxes, some reaching beyond the stored bounds [0, 10 + max_extent]^2.
  for (int q = 0; q < 40; ++q) {
    const double x = uniform(rng, -3.0, 13.0), y = uniform(rng, -3.0, 13.0);
    const double w = uniform(rng, 0.0, 4.0), h = uniform(rng, 0.0, 4.0);
    check_query(grid, boxes, {{x, y}, {x + w, y + h}});
  }
}

TEST_CASE("UniformGrid: queries outside the bounds, touching and point boxes", "[kernels][broad_phase]") {
  // Four unit boxes on a 2 x 2 pattern with gaps of 1: [0,1]^2, [2,3]x[0,1], [0,1]x[2,3], [2,3]^2.
  const std::vector<Box> boxes{{{0.0, 0.0}, {1.0, 1.0}}, {{2.0, 0.0}, {3.0, 1.0}},
                               {{0.0, 2.0}, {1.0, 3.0}}, {{2.0, 2.0}, {3.0, 3.0}}};
  UniformGrid grid;
  grid.build(boxes);  // default cell: mean extent 1, 4 x 4 cells over [0, 3]^2 (within the cap 4 n + 16)
  // Far outside: the clamped cells are visited, but no box overlaps.
  CHECK(grid_answer(grid, {{50.0, 50.0}, {60.0, 60.0}}).empty());
  CHECK(grid_answer(grid, {{-60.0, -60.0}, {-50.0, -50.0}}).empty());
  // A box covering everything, from outside on all sides: all four, once each.
  check_query(grid, boxes, {{-5.0, -5.0}, {8.0, 8.0}});
  CHECK(grid_answer(grid, {{-5.0, -5.0}, {8.0, 8.0}}).size() == 4);
  // In the gap between the boxes: nothing.
  CHECK(grid_answer(grid, {{1.25, 1.25}, {1.75, 1.75}}).empty());
  // Touching the right edge of box 0 and the left edge of box 1 (x = 1 and x = 2): both.
  std::vector<std::size_t> touching = grid_answer(grid, {{1.0, 0.5}, {2.0, 0.5}});
  std::sort(touching.begin(), touching.end());
  CHECK(touching == std::vector<std::size_t>{0, 1});
  // A point query between the boxes, (1.5, 1.5): nothing; at the corner (1, 1) of box 0: box 0.
  CHECK(grid_answer(grid, {{1.5, 1.5}, {1.5, 1.5}}).empty());
  CHECK(grid_answer(grid, {{1.0, 1.0}, {1.0, 1.0}}) == std::vector<std::size_t>{0});

  // Point boxes (zero extent: the default cell falls back to the bounds' size).
  const std::vector<Box> points{{{0.0, 0.0}, {0.0, 0.0}}, {{1.0, 1.0}, {1.0, 1.0}}, {{1.0, 1.0}, {1.0, 1.0}}};
  UniformGrid point_grid;
  point_grid.build(points);
  std::vector<std::size_t> at_one = grid_answer(point_grid, {{0.5, 0.5}, {1.0, 1.0}});
  std::sort(at_one.begin(), at_one.end());
  CHECK(at_one == std::vector<std::size_t>{1, 2});  // two items at the same point, each once
  check_query(point_grid, points, {{-1.0, -1.0}, {2.0, 2.0}});

  // An empty grid visits nothing; rebuilding with other boxes forgets the old ones.
  const std::vector<Box> none;
  UniformGrid empty_grid;
  empty_grid.build(none);
  CHECK(grid_answer(empty_grid, {{-1.0, -1.0}, {1.0, 1.0}}).empty());
  grid.build(points);
  check_query(grid, points, {{-5.0, -5.0}, {8.0, 8.0}});
}

TEST_CASE("UniformGrid: many queries in a row keep reporting each item once", "[kernels][broad_phase]") {
  // The once-per-query guarantee rests on per-item stamps of a query counter; repeated queries of the
  // same grid must not carry a stamp over from one query to the next.
  std::mt19937 rng(7u);
  const std::vector<Box> boxes = random_boxes(rng, 30, 2.0);
  UniformGrid grid;
  grid.build(boxes, 0.4);
  const Box everything{{-1.0, -1.0}, {13.0, 13.0}};
  for (int repeat = 0; repeat < 200; ++repeat) {
    const std::vector<std::size_t> found = grid_answer(grid, everything);
    REQUIRE(found.size() == boxes.size());
  }
  check_query(grid, boxes, everything);
}
