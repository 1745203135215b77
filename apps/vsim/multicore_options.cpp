// The options of `vsim --target multicore` (a Meld program on a simulated chip), and the checks
// that keep world-only options away from it.
#include <charconv>
#include <string>

#include "options.hpp"
#include "support/text.hpp"

namespace vsim {

namespace {

void parseCoreList(std::string_view text, std::vector<unsigned>& cores) {
  cores.clear();
  forEachListItem(text, [&](std::string_view item) {
    unsigned n = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), n);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || n == 0 || n > 1024)
      throw UsageError("--cores wants core counts from 1 to 1024 (N or N,M,...), got '" + std::string(item) +
                       "'");
    cores.push_back(n);
  });
}

// --costs rule=150,send=200,...: each given cost replaces the calibrated default.
void parseCosts(std::string_view text, multicore::CoreCosts& costs) {
  forEachListItem(text, [&](std::string_view item) {
    const auto eq = item.find('=');
    if (eq == std::string_view::npos)
      throw UsageError("--costs wants NAME=NS pairs like rule=150,send=200, got '" + std::string(item) + "'");
    const std::string_view name = item.substr(0, eq);
    for (const multicore::CostName& c : multicore::kCostNames)
      if (name == c.name) {
        costs.*c.cost = parseNumber("--costs " + std::string(name), item.substr(eq + 1), false, 1e12,
                                    "a non-negative number");
        return;
      }
    std::string known;
    for (const multicore::CostName& c : multicore::kCostNames)
      known += std::string(known.empty() ? "" : ", ") + c.name;
    throw UsageError("--costs: unknown cost '" + std::string(name) + "' (" + known + ")");
  });
}

}  // namespace

bool Options::isMulticore() const { return support::sameIgnoringCase(target, "multicore"); }

bool parseMulticoreOption(std::string_view arg, const std::function<std::string_view()>& value,
                          MulticoreOptions& m) {
  if (arg == "--cores") {
    parseCoreList(value(), m.cores);
  } else if (arg == "--topology") {
    const std::string_view name = value();
    const auto t = multicore::parseTopology(name);
    if (!t) throw UsageError("--topology is mesh, ring or full, got '" + std::string(name) + "'");
    m.chip.topology = *t;
  } else if (arg == "--hop-latency") {
    m.chip.hopLatency =
        parseNumber("--hop-latency", value(), false, 1e12, "a non-negative number of nanoseconds");
  } else if (arg == "--costs") {
    parseCosts(value(), m.chip.costs);
  } else if (arg == "--no-steal") {
    m.chip.stealing = false;
  } else if (arg == "--profile") {
    m.profile = value();
    if (m.profile.empty()) throw UsageError("--profile needs a file name");
  } else {
    return false;
  }
  return true;
}

void checkMulticoreOptions(Options& o, bool multicoreOptionGiven) {
  if (!o.isMulticore()) {
    if (multicoreOptionGiven || !o.programArgs.empty())
      throw UsageError(
          "--cores, --topology, --hop-latency, --costs, --no-steal, --profile and `-- ARGS` "
          "are for --target multicore");
    return;
  }
  if (!o.world.empty())
    throw UsageError("--target multicore runs a Meld program on its own graph: no world file (got '" +
                     o.world + "')");
  if (o.program.empty()) throw UsageError("--target multicore needs --program PROG.meld|PROG.mbc|PROG.so");
  auto refuse = [](bool given, const char* option) {
    if (given) throw UsageError(std::string(option) + " is for worlds, not for --target multicore");
  };
  refuse(!o.code.empty(), "--code");
  refuse(!o.why.empty(), "--why");
  refuse(!o.taps.empty(), "--tap");
  refuse(o.trace, "--trace");
  refuse(!o.exportFile.empty(), "--export");
  refuse(!o.gltfFile.empty(), "--export-gltf");
  refuse(o.checkStability, "--check-stability");
  refuse(!o.mobilesCsv.empty(), "--mobiles-csv");
  refuse(o.physicsStep > 0, "--physics-step");
  refuse(!o.jsonFile.empty(), "--json");
  refuse(o.until.has_value(), "--until");
  refuse(o.timePerRule >= 0, "--time-per-rule (see --costs)");
  if (o.multicore.cores.empty()) o.multicore.cores = {4};
}

}  // namespace vsim
