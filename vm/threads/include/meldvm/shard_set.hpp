// What the shards of one run (threads, or the cores of a simulated chip) hold together: the dump
// in node order, the collection of created nodes (§6.10) over all of them, their statistics.
#pragma once

#include <string>
#include <vector>

#include "meldvm/machine.hpp"
#include "meldvm/node_directory.hpp"

namespace meldvm {

// shards[t] is thread (core) t's Machine.
std::string dumpShards(const Program& program, const threads::NodeDirectory& directory,
                       const std::vector<const Machine*>& shards);
// §6.10 over all shards: removes each created node with no facts that no fact anywhere refers to.
void collectGarbageNodes(const std::vector<Machine*>& shards);
MachineStats sumStats(const std::vector<const Machine*>& shards);

}  // namespace meldvm
