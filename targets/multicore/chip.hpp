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

// Nanoseconds of core time. The defaults are fitted by bench/multicore/calibrate.sh to `meld -j 1`
// and `-j 2` runs of the five B2 programs on the project's 2-core machine (2026-11-29, against the
// runtime of issue 29's sixteenth session; its README has the fit, how well it predicts, and how
// to redo it for another machine). A zero is what the fit found: that count added nothing the
// others did not already explain.
struct CoreCosts {
  double nodeRun = 0;         // choosing a node and running it, beyond what its rules cost
  double rule = 44.1;         // one rule firing
  double fact = 0;            // one fact derived (stored, indexed, or queued for its node)
  double tried = 30.34;       // one fact a rule looked at, whether it matched or not
  double send = 0;            // one fact sent to another core (into the batch)
  double receive = 0;         // one fact received from another core (stored or posted)
  double byte = 0;            // one byte of such a fact's record, at each end
  double rebalance = 1262370; // one work-stealing round (all cores wait in it until the packing ends)
  double nodeMoved = 0;       // one node moved by it, beyond its bytes
  double movedByte = 5.74;    // one byte of a moving node's record (its facts and messages), at each end
                              // (packed while all wait, unpacked by its taker alone)
  // Not ns: how much slower a core runs while all the others are busy too (shared caches and
  // memory), 0.3 = 30 %; with k of N cores busy, a run costs (1 + contention (k-1)/(N-1)) times more.
  double contention = 0.04;
};

// The costs by name: vsim's --costs NAME=V, its report and bench/multicore/fit_costs.py's output
// all use these names.
struct CostName {
  const char* name;
  double CoreCosts::*cost;
};
inline constexpr CostName kCostNames[] = {{"node", &CoreCosts::nodeRun},
                                          {"rule", &CoreCosts::rule},
                                          {"fact", &CoreCosts::fact},
                                          {"tried", &CoreCosts::tried},
                                          {"send", &CoreCosts::send},
                                          {"receive", &CoreCosts::receive},
                                          {"byte", &CoreCosts::byte},
                                          {"rebalance", &CoreCosts::rebalance},
                                          {"move", &CoreCosts::nodeMoved},
                                          {"movebyte", &CoreCosts::movedByte},
                                          {"contention", &CoreCosts::contention}};

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
