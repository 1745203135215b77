// The options of `vsim --target multicore` (a Meld program on a simulated chip), and the checks
// that keep world-only options away from it.
#include <charconv>
#include <cstdlib>
#include <string>

#include "options.hpp"
#include "support/text.hpp"

namespace vsim {

namespace {

double parseNumber(std::string_view option, std::string_view text, const char* what = "number") {
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !(v >= 0) || v > 1e12)
    throw UsageError(std::string(option) + " wants a non-negative " + what + ", got '" + s + "'");
  return v;
}

void parseCoreList(std::string_view text, std::vector<unsigned>& cores) {
  cores.clear();
  for (;;) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    unsigned n = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), n);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || n == 0 || n > 1024)
      throw UsageError("--cores wants core counts from 1 to 1024 (N or N,M,...), got '" + std::string(item) +
                       "'");
    cores.push_back(n);
    if (comma == std::string_view::npos) return;
    text.remove_prefix(comma + 1);
  }
}

// --costs node=120,rule=150,...: each given cost replaces the calibrated default.
void parseCosts(std::string_view text, multicore::CoreCosts& costs) {
  for (;;) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos)
      throw UsageError("--costs wants NAME=NS pairs like rule=150,send=200, got '" + std::string(item) + "'");
    const std::string_view name = item.substr(0, eq);
    const double v = parseNumber("--costs " + std::string(name), item.substr(eq + 1));
    if (name == "node")
      costs.nodeRun = v;
    else if (name == "rule")
      costs.rule = v;
    else if (name == "fact")
      costs.fact = v;
    else if (name == "send")
      costs.send = v;
    else if (name == "receive")
      costs.receive = v;
    else if (name == "rebalance")
      costs.rebalance = v;
    else if (name == "move")
      costs.nodeMoved = v;
    else if (name == "contention")
      costs.contention = v;
    else if (name == "byte")
      costs.byte = v;
    else if (name == "tried")
      costs.tried = v;
    else
      throw UsageError("--costs: unknown cost '" + std::string(name) +
                       "' (node, rule, fact, tried, send, receive, byte, rebalance, move, contention)");
    if (comma == std::string_view::npos) return;
    text.remove_prefix(comma + 1);
  }
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
    m.chip.hopLatency = parseNumber("--hop-latency", value(), "number of nanoseconds");
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
  if (o.program.empty()) throw UsageError("--target multicore needs --program PROG.meld|PROG.mbc");
  auto refuse = [](bool given, const char* option) {
    if (given) throw UsageError(std::string(option) + " is for worlds, not for --target multicore");
  };
  refuse(!o.code.empty(), "--code");
  refuse(!o.why.empty(), "--why");
  refuse(!o.taps.empty(), "--tap");
  refuse(o.trace, "--trace");
  refuse(!o.exportFile.empty(), "--export");
  refuse(!o.jsonFile.empty(), "--json");
  refuse(o.until.has_value(), "--until");
  refuse(o.timePerRule >= 0, "--time-per-rule (see --costs)");
  if (o.multicore.cores.empty()) o.multicore.cores = {4};
}

}  // namespace vsim
