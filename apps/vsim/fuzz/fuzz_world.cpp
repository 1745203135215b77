// Fuzz entry point for world files as `vsim` meets them: any text must either be refused with an
// XmlWorldError (file:line:col) or load, build its simulation on the target it names (unknown
// targets are the front end's business: Blinky Blocks is used then) and run the colour flood for
// a bounded simulated time. A crash, a sanitizer report or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "simcore/simulation.hpp"
#include "simcore/xml_world.hpp"
#include "targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  simcore::WorldDescription world;
  try {
    world = simcore::parseWorldXml(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.xml");
  } catch (const simcore::XmlWorldError&) {
    return 0;
  }
  auto target = targets::makeTarget(world.target);
  if (!target) target = targets::makeTarget("blinkyblocks");
  // Worlds of millions of cells are legal; the fuzzer keeps to what a test can build quickly.
  if (std::uint64_t(world.grid.x) * std::uint64_t(world.grid.y) * std::uint64_t(world.grid.z) > (1u << 22))
    return 0;
  simcore::Simulation sim(*target, world.grid);
  try {
    simcore::populateSimulation(world, sim);
  } catch (const simcore::XmlWorldError&) {
    return 0;
  }
  sim.runUntil(simcore::SimTime(10) * 1000000000);
  return 0;
}
