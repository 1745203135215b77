// The multicore target's chip (vsim --target multicore): N cores on an interconnect, and what
// work costs on them. Nothing here knows Meld: the simulator (chip_simulator.hpp) runs whatever a
// CoreWorkload gives it; vsim plugs the Meld VM's shards in.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace multicore {

// mesh: cores on a square-ish 2-D grid (width ceil(sqrt N), row-major), hops = Manhattan
// distance; ring: hops = the shorter way round; full: every pair one hop apart.
enum class Topology { Mesh, Ring, Full };
std::optional<Topology> parseTopology(std::string_view name);
const char* topologyName(Topology t);

// Nanoseconds of core time. The defaults are calibrated on the project's 2-core machine by
// bench/multicore/calibrate.sh (its README has the fit and how to redo it for another machine).
struct CoreCosts {
  double nodeRun = 120;  // choosing a node and running it, beyond what its rules cost
  double rule = 150;     // one rule firing
  double fact = 100;     // one fact derived (stored, indexed, or queued for its node)
  double send = 150;     // one fact sent to another core (encoded into the batch)
  double receive = 200;  // one fact received from another core (decoded, stored)
  double rebalance = 20000;  // one work-stealing round (all cores wait in it)
  double nodeMoved = 2000;   // one node moved by it (its facts travel along)
};

struct ChipSpec {
  unsigned cores = 1;
  Topology topology = Topology::Mesh;
  double hopLatency = 50;  // ns for a batch of facts to cross one hop
  CoreCosts costs;
  bool stealing = true;  // idle cores take nodes from loaded ones, as the threaded runtime does
};

// Hops between two cores (0 for the same core).
unsigned hops(const ChipSpec& chip, unsigned from, unsigned to);
// The mesh's row length.
unsigned meshWidth(unsigned cores);

}  // namespace multicore
