#define BOOST_TEST_MODULE simcore_flood
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <set>
#include <tuple>
#include <vector>

#include "test_support.hpp"

using namespace simcore;
using testsupport::Script;

namespace {

constexpr std::uint32_t kRed = 0xFF0000;

// Flood from block 0: the first message colors a block red and is forwarded on every face.
struct FloodState {
  std::uint8_t reached;
};
void floodOut(vs_ctx* c) {
  static_cast<FloodState*>(c->state)->reached = 1;
  vs_set_color(c, kRed);
  const std::uint8_t token = 1;
  vs_send_all(c, &token, 1, 0);
}
void floodStart(vs_ctx* c) {
  if (c->block == 0) floodOut(c);
}
void floodEvent(vs_ctx* c, const vs_event* ev) {
  if (ev->kind == VS_EV_MESSAGE && !static_cast<FloodState*>(c->state)->reached) floodOut(c);
}
const vs_blockcode kFlood = {VS_ABI_VERSION, "flood", sizeof(FloodState), &floodStart, &floodEvent,
                             nullptr,        nullptr};

// The connected component of `start` computed independently of the kernel: face-adjacent cells
// (4 in the plane, 6 in space).
std::set<std::size_t> componentOf(const std::vector<Cell>& cells, std::size_t start, bool planar) {
  std::set<std::size_t> seen{start};
  std::deque<std::size_t> todo{start};
  while (!todo.empty()) {
    const Cell a = cells[todo.front()];
    todo.pop_front();
    for (std::size_t j = 0; j < cells.size(); ++j) {
      const Cell& b = cells[j];
      const int d = std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z);
      if (d == 1 && (!planar || a.z == b.z) && seen.insert(j).second) todo.push_back(j);
    }
  }
  return seen;
}

// Runs the flood on `cells` and checks that exactly block 0's component turned red.
// Returns the size of the component.
std::size_t checkFlood(const TargetSpec& target, GridSize size, const std::vector<Cell>& cells,
                       std::size_t expectedSize) {
  auto sim = testsupport::makeSim(target, size, cells);
  sim->setBlockCode(&kFlood);
  const std::uint32_t before = sim->world().block(0).color;
  BOOST_REQUIRE_NE(before, kRed);
  sim->runUntilEmpty();
  const auto comp = componentOf(cells, 0, target.name == "smartblocks");
  if (expectedSize) BOOST_CHECK_EQUAL(comp.size(), expectedSize);
  std::size_t red = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const bool isRed = sim->world().block(BlockId(i)).color == kRed;
    red += isRed;
    BOOST_CHECK_MESSAGE(isRed == (comp.count(i) > 0), "block " << i << " at (" << cells[i].x << ","
                                                               << cells[i].y << "," << cells[i].z
                                                               << ") red=" << isRed);
    BOOST_CHECK_EQUAL(static_cast<FloodState*>(sim->blockState(BlockId(i)))->reached, comp.count(i) ? 1 : 0);
  }
  BOOST_CHECK_EQUAL(red, comp.size());
  const Statistics& st = sim->statistics();
  BOOST_CHECK_EQUAL(st.messagesDropped, 0u);
  BOOST_CHECK_EQUAL(st.messagesReceived, st.messagesSent);
  BOOST_CHECK_GE(st.messagesSent, comp.size() - 1);
  return comp.size();
}

}  // namespace

BOOST_AUTO_TEST_CASE(blinky_flood_colors_exactly_the_component_of_block_0) {
  // Three components in a 6x6x4 box: a 3x3 slab with a tower on it (block 0 in the slab), an
  // L-shaped bar that touches the slab only along an edge (diagonal: not attached), and a lone
  // block above the slab with a gap of one cell.
  std::vector<Cell> cells;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y) cells.push_back({x, y, 0});
  cells.push_back({1, 1, 1});
  cells.push_back({1, 1, 2});
  const std::size_t slab = cells.size();
  cells.push_back({3, 3, 1});  // diagonal to (2,2,0): edge contact only
  cells.push_back({4, 3, 1});
  cells.push_back({5, 3, 1});
  cells.push_back({5, 4, 1});
  cells.push_back({0, 0, 2});  // above (0,0,0) with an empty cell between
  checkFlood(targets::blinkyBlocksTarget(), {6, 6, 4}, cells, slab);
}

BOOST_AUTO_TEST_CASE(smart_blocks_flood_colors_exactly_the_component_of_block_0) {
  // Two components touching only at corners, plus a spiral that comes back close to block 0.
  const std::vector<Cell> cells = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0},
                                   {3, 3, 0}, {4, 3, 0}, {4, 4, 0}, {0, 2, 0}, {0, 4, 0}, {1, 4, 0}};
  // (0,2,0) is attached to (1,2,0): in the component. (3,3) touches (2,2) at a corner only.
  checkFlood(targets::smartBlocksTarget(), {5, 5, 1}, cells, 7);
}

BOOST_AUTO_TEST_CASE(flood_on_random_worlds_matches_breadth_first_search) {
  int partial = 0;  // worlds where the flood had to stop short of some blocks
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    for (bool blinky : {false, true}) {
      BOOST_TEST_CONTEXT("seed " << seed << (blinky ? " blinky" : " smart")) {
        const GridSize size = blinky ? GridSize{7, 7, 3} : GridSize{14, 14, 1};
        std::uint64_t st = BlockRng::initialState(seed, 4242);
        std::vector<Cell> cells;
        std::set<std::tuple<int, int, int>> used;
        const std::uint32_t n = std::uint32_t(size.x * size.y * size.z);
        const std::uint32_t want = n * 45 / 100;  // near the percolation threshold: several components
        while (cells.size() < want) {
          const std::uint32_t c = BlockRng::below(st, 4242, n);
          const Cell cell{std::int32_t(c % std::uint32_t(size.x)),
                          std::int32_t((c / std::uint32_t(size.x)) % std::uint32_t(size.y)),
                          std::int32_t(c / std::uint32_t(size.x * size.y))};
          if (used.insert({cell.x, cell.y, cell.z}).second) cells.push_back(cell);
        }
        const std::size_t reached =
            checkFlood(blinky ? targets::blinkyBlocksTarget() : targets::smartBlocksTarget(), size, cells, 0);
        partial += reached > 1 && reached < cells.size();
      }
    }
  }
  BOOST_CHECK_GE(partial, 12);
}
