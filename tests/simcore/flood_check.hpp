// Shared by the Catoms tests: runs the color_flood example BlockCode (examples/c/color_flood.c) on
// an example world and checks every block's hop count against a breadth-first search computed here,
// apart from the kernel and its lattice classes: two catoms touch when the centres given by the
// test's own formula are one diameter apart.
#pragma once

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "simcore/blockcode_library.hpp"
#include "simcore/simulation.hpp"
#include "simcore/xml_world.hpp"
#include "targets.hpp"

namespace floodcheck {

// color_flood.c's per-block state.
struct FloodState {
  std::uint32_t wave, origin, hops;
};

inline const std::string kWorlds = std::string(MELD_SOURCE_DIR) + "/examples/worlds/";
inline const std::string kColorFlood = std::string(MELD_BINARY_DIR) + "/blockcodes/color_flood.so";

using Center = std::function<simcore::Vec3(const simcore::Cell&)>;

// Hop distance from block `from` to every block (-1: unreachable), by geometry alone.
inline std::vector<int> hopDistances(const std::vector<simcore::Cell>& cells, std::size_t from,
                                     const Center& center) {
  std::vector<simcore::Vec3> c;
  for (const simcore::Cell& cell : cells) c.push_back(center(cell));
  std::vector<int> dist(cells.size(), -1);
  std::deque<std::size_t> todo{from};
  dist[from] = 0;
  while (!todo.empty()) {
    const std::size_t a = todo.front();
    todo.pop_front();
    for (std::size_t b = 0; b < cells.size(); ++b) {
      const double dx = c[a].x - c[b].x, dy = c[a].y - c[b].y, dz = c[a].z - c[b].z;
      if (dist[b] < 0 && std::fabs(std::sqrt(dx * dx + dy * dy + dz * dz) - 1.0) < 1e-9) {
        dist[b] = dist[a] + 1;
        todo.push_back(b);
      }
    }
  }
  return dist;
}

// Loads examples/worlds/`file`, runs color_flood until `until` and checks that every block took
// part in wave `wave` started by block `origin`, at its BFS distance from it. Returns the number of
// blocks.
inline std::size_t checkFlood(const std::string& file, const Center& center, simcore::SimTime until,
                              simcore::BlockId origin, std::uint32_t wave) {
  const simcore::WorldDescription d = simcore::loadWorldXml(kWorlds + file);
  const std::optional<simcore::TargetSpec> target = targets::makeTarget(d.target);
  BOOST_REQUIRE(target.has_value());
  // Declared before the simulation: the code table must outlive it.
  simcore::BlockCodeLibrary library = simcore::BlockCodeLibrary::open(kColorFlood);
  simcore::Simulation sim(*target, d.grid);
  simcore::populateSimulation(d, sim);
  sim.setBlockCode(library.code());
  sim.runUntil(until);
  std::vector<simcore::Cell> cells;
  for (const simcore::BlockDescription& b : d.blocks) cells.push_back(b.cell);
  const std::vector<int> dist = hopDistances(cells, origin, center);
  for (simcore::BlockId id = 0; id < cells.size(); ++id) {
    const auto* s = static_cast<const FloodState*>(sim.blockState(id));
    BOOST_TEST_CONTEXT(file << ": block " << id) {
      BOOST_TEST(dist[id] >= 0);  // the example worlds are connected
      BOOST_TEST(s->wave == wave);
      BOOST_TEST(s->origin == origin);
      BOOST_TEST(int(s->hops) == dist[id]);
    }
  }
  BOOST_TEST(sim.statistics().messagesDropped == 0u);
  return cells.size();
}

}  // namespace floodcheck
