// A Meld program on a simulated world, in-process: compile the source with node ids = block ids,
// build the world, run, read facts and colors.
#pragma once

#include <boost/test/unit_test.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../meldc/compile_source.hpp"
#include "meldvm/block_runtime.hpp"
#include "simcore/simulation.hpp"
#include "targets.hpp"

namespace robots {

// Node ids = block ids.
inline std::unique_ptr<meldvm::Program> compile(const std::string& source) {
  return compileSource(source, true);
}

struct World {
  std::unique_ptr<meldvm::Program> program;
  std::unique_ptr<simcore::Simulation> sim;
  std::unique_ptr<meldvm::BlockRuntime> vm;

  World(const std::string& target, const std::vector<simcore::Cell>& cells, const std::string& source,
        meldvm::BlockRuntimeOptions options = {}, simcore::GridSize grid = {20, 20, 20},
        std::uint64_t seed = 1) {
    program = compile(source);
    const auto spec = targets::makeTarget(target);
    BOOST_REQUIRE(spec);
    simcore::SimulationConfig config;
    config.seed = seed;
    sim = std::make_unique<simcore::Simulation>(*spec, grid, config);
    for (const simcore::Cell& c : cells) BOOST_REQUIRE(sim->addBlock(c) != simcore::kNoBlock);
    vm = std::make_unique<meldvm::BlockRuntime>(*program, std::uint32_t(cells.size()), options);
    sim->setBlockCode(vm->blockcode());
  }
  std::string dump() const {
    std::ostringstream s;
    vm->dump(s);
    return s.str();
  }
  // The dump lines of one block (without its id line). Fact lines always hold a parenthesis, so
  // a line of digits is a block id.
  std::string facts(std::uint32_t block) const {
    std::istringstream in(dump());
    std::string line, out;
    bool mine = false;
    while (std::getline(in, line)) {
      if (!line.empty() && line.find_first_not_of("0123456789") == std::string::npos)
        mine = line == std::to_string(block);
      else if (mine)
        out += line + "\n";
    }
    return out;
  }
  std::uint32_t color(std::uint32_t block) const { return sim->world().block(block).color; }
};

// Blocks on a line along x.
inline std::vector<simcore::Cell> line(int n) {
  std::vector<simcore::Cell> cells;
  for (int i = 0; i < n; ++i) cells.push_back({i, 0, 0});
  return cells;
}

}  // namespace robots
