#include "options.hpp"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace vsim {

const char* usageText() {
  return R"(usage: vsim WORLD.xml [--code LIB.so | --program PROG.meld|PROG.mbc|PROG.so] [options]
       vsim --target multicore --program PROG.meld|PROG.mbc|PROG.so [--cores N[,N...]] [options] [-- ARGS]

Runs the block program LIB.so, or the Meld program PROG (one Meld node per block, node id = block
id; a .meld file is compiled first), on every block of the world WORLD.xml (headless) and prints a
summary: target, blocks, events, simulated and wall time, events/s, the run fingerprint and a
histogram of the final colors (plus each block's color for worlds of at most 20 blocks).
Without --code or --program, the world's code= (a C BlockCode) or program= (Meld) is run.

Without --until the run goes on until no event is pending. A block program that never goes
quiet (timers that re-arm, endless messages) then runs forever: give --until (Ctrl-C stops a run
early and still prints the summary).

options:
  --code LIB.so         block program (C BlockCode .so); overrides the world's code= attribute
  --program PROG        Meld program (.meld, compiled with node ids = block ids, or .mbc from
                        `meldc --robots`, or .so from `meldc --robots --emit=native`: native
                        code); the target's include file is found by `include`
  --jit                 with a .meld or .mbc program: compile its rules to native code in
                        memory first (LLVM) and run that; the same run as the bytecode
  --dump                with a Meld program: print every block's final facts (the `meld --dump`
                        format) after the summary
  --why FACT@BLOCK      with a Meld program: after the run, print why the fact exists on that
                        block, like --why 'dist(2)@24' (values as --dump prints them): the rule
                        (FILE:LINE, the block it ran at, the simulated time), the facts it matched,
                        down to the axioms (FILE:LINE) and the sensed facts; a fact from a
                        neighbour names the block that sent it. Repeatable
  --time-per-rule T     with a Meld program: simulated computing time of one rule firing (target
                        default: 10us Blinky/Smart Blocks, 1us Catoms); a node run's messages
                        leave after its rules' time
  --palette visiblesim|lm
                        with --program: colours of setColor2 (default visiblesim: C mod 12)
  -I DIR                with a Meld program: include directory for the .meld compiler
  --target NAME         blinkyblocks, smartblocks, catoms2d or catoms3d; overrides the world's
                        target= attribute
                        (default when neither says: blinkyblocks)
  --until T             stop at simulated time T: 10s, 1500ms, 2min, 250us (bare number = s)
  --seed S              seed of the per-block random streams (default: the world's, else 1)
  --fes heap|calendar|ladder
                        future-event set implementation (default ladder, the fastest on
                        the benchmarks; same results, speed only)
  --link-rate BPS       link data rate in bit/s (target default: 38400 Blinky, 1e6 the others)
  --link-latency T      extra delay after each transmission (default 0)
  --link-jitter T       random extra delay in [0, T]; never reorders a link (default 0)
  --motion-time T       duration of one motion (Smart Blocks, Catoms 2D and 3D; default 1s)
  --tap ID@T            tap block ID at time T (repeatable, or comma-separated: 0@1s,3@2s)
  --stats               print the kernel statistics (events per kind, messages, queue size)
  --json FILE           write the summary and statistics as JSON ("-" = stdout, no text summary)
  --export FILE         write the final configuration as a world XML ("-" = stdout)
  --export-gltf FILE    write the final configuration as glTF 2.0 (FILE.glb, binary) for
                        renderers such as Blender: a node per block, a material per colour
  --mobiles-csv FILE    worlds with mobiles (Smart Blocks and air jets, <mobileList>): write one
                        line per physics step and mobile, `t,mobile,x,y,angle` (s, mm, mm,
                        degrees) after a `t,mobile,x,y,angle` header ("-" = stdout)
  --physics-step T      the physics' Euler step (default 1ms)
  --check-stability     the reality checker (Blinky Blocks, Catoms 2D and 3D, under gravity): is
                        every structure on the floor, over its floor contacts, and is every link
                        strong enough for what hangs from it? Prints `stability: stable` or
                        `stability: unstable (...)` with the blocks, links and pivot axes for the
                        final configuration (exit status 4 when unstable), and a warning for each
                        motion whose result would not hold. Without a block program the world is
                        checked as it is, and nothing runs
  --refuse-unstable     --check-stability, and a motion whose result would not hold is refused
                        (the block program gets VS_ERR_UNSTABLE)
  --trace FILTER        trace the run: 'blocks=0,5-9;kinds=message,tap;from=1s;to=2s'
                        (every clause optional; 'all' traces everything). Kinds: start, message,
                        neighbor-added, neighbor-removed, tap, timer, motion-end, sensor, mobile,
                        physics-step, send, drop, color, motion, trace; groups: all, events,
                        neighbor
  --trace-format text|json
                        one readable line or one JSON object per record (default text)
  --trace-file FILE     where the trace goes (default stderr; "-" = stdout); --trace-format and
                        --trace-file alone trace everything
  --quiet, -q           no summary, no warnings, no progress line (errors are still printed)
  --no-progress         no progress line (shown on a terminal for runs longer than a second)
  --help, -h            this text
  --version             the version

the multicore target (--target multicore, no world file): the Meld program on its own graph (as
`meld` runs it) on a simulated chip of N cores; nodes are placed as `meld -j N` places them on
threads, a rule firing and a fact cost core time, a fact for another core's node crosses the
interconnect, idle cores steal nodes. Prints the predicted run time, the speedup over one core
(a one-core run is simulated too) and each core's busy/idle/steal shares; with a list of counts,
one line per count (output, dump and profile are those of the last count).
  --cores N[,N...]      cores of the chip, 1 to 1024 (default 4)
  --topology mesh|ring|full
                        interconnect: 2-D mesh (hops = Manhattan distance), ring, or every pair
                        one hop apart (default mesh)
  --hop-latency NS      nanoseconds for a batch of facts to cross one hop (default 50)
  --costs NAME=NS,...   core time of: node (a node run), rule (a rule firing), fact (a fact
                        derived), tried (a fact a rule looked at, matching or not), send /
                        receive (a fact to / from another core), byte (a byte of such a fact,
                        at each end), rebalance (a work-stealing round), move (a node moved),
                        movebyte (a byte of a moving node's facts and messages, at each end);
                        and contention=F: a run is (1 + F) times slower while every other core
                        is busy too (shared caches, memory). Defaults: fitted on the project's
                        2-core machine (bench/multicore/README.md); vsim prints those it used
  --no-steal            no work stealing (the static partition only)
  --profile FILE.json   the run's per-core timeline in the `meld --profile` format
  --dump                the final facts, as `meld --dump` prints them
  --seed S, -I DIR, --quiet as above; -- ARGS: the program's arguments (@arg1 ...)

exit codes:
  0    the run completed (queue empty or --until reached)
  1    runtime error: the simulation failed, or an output file could not be written
  2    usage error: bad command line, bad trace filter, no block code given
  3    input error: bad or missing world file, unknown target in it, bad block code .so
  4    --check-stability: the final configuration does not stand
  130  interrupted (Ctrl-C); the summary of the partial run is printed

examples:
  vsim examples/worlds/color-flood.xml                  (the world names its code=color_flood.so)
  vsim examples/worlds/tap-cycle.xml --code tap_cycle.so \
       --tap 2@1s --trace 'kinds=tap,color'
  vsim examples/worlds/meld-gradient-tap.xml --program examples/meld/gradient-tap.meld \
       --tap 0@1s --dump
  vsim examples/worlds/stability-overhang.xml --check-stability
  bench/meld/pagerank/gen.py --nodes 1000 --iterations 10 -o pr.meld
  vsim --target multicore --program pr.meld --cores 1,2,4,8,16,32
)";
}

namespace {

std::uint64_t parseCount(std::string_view option, std::string_view text) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw UsageError(std::string(option) + " wants a non-negative integer, got '" + std::string(text) + "'");
  return v;
}

simcore::SimTime parseTime(std::string_view option, std::string_view text) {
  const auto t = simcore::parseDuration(text);
  if (!t)
    throw UsageError(std::string(option) + " wants a duration like 10s, 1500ms or 2min, got '" +
                     std::string(text) + "'");
  return *t;
}

void parseTaps(std::string_view text, std::vector<TapRequest>& taps) {
  forEachListItem(text, [&](std::string_view item) {
    const auto at = item.find('@');
    if (at == std::string_view::npos)
      throw UsageError("--tap wants BLOCK@TIME like 3@1.5s, got '" + std::string(item) + "'");
    const std::uint64_t block = parseCount("--tap block", item.substr(0, at));
    if (block > 0xFFFFFFFEull) throw UsageError("--tap: block id " + std::to_string(block) + " is too large");
    taps.push_back({std::uint32_t(block), parseTime("--tap time", item.substr(at + 1))});
  });
}

}  // namespace

double parseNumber(std::string_view option, std::string_view text, bool positive, double max,
                   const char* what) {
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !(positive ? v > 0 : v >= 0) || v > max)
    throw UsageError(std::string(option) + " wants " + what + ", got '" + s + "'");
  return v;
}

Options parseOptions(int argc, char** argv, bool worldRequired) {
  Options o;
  bool traceFormatOrFile = false, multicoreOption = false;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    // Both "--opt value" and "--opt=value".
    std::optional<std::string_view> inlineValue;
    if (arg.size() > 2 && arg.substr(0, 2) == "--") {
      const auto eq = arg.find('=');
      if (eq != std::string_view::npos) {
        inlineValue = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
      }
    }
    auto value = [&]() -> std::string_view {
      if (inlineValue) return *inlineValue;
      if (i + 1 >= argc) throw UsageError(std::string(arg) + " needs a value");
      return argv[++i];
    };
    auto flag = [&] {
      if (inlineValue) throw UsageError(std::string(arg) + " takes no value");
    };

    if (arg == "--") {  // the rest: the Meld program's arguments (@arg1 ...)
      for (++i; i < argc; ++i) o.programArgs.emplace_back(argv[i]);
      break;
    }
    if (arg == "--no-steal") flag();
    if (parseMulticoreOption(arg, value, o.multicore)) {
      multicoreOption = true;
      continue;
    }
    if (arg == "--help" || arg == "-h")
      flag(), o.help = true;
    else if (arg == "--version")
      flag(), o.version = true;
    else if (arg == "--quiet" || arg == "-q")
      flag(), o.quiet = true;
    else if (arg == "--no-progress")
      flag(), o.progress = false;
    else if (arg == "--stats")
      flag(), o.stats = true;
    else if (arg == "--code")
      o.code = value();
    else if (arg == "--program")
      o.program = value();
    else if (arg == "--dump")
      flag(), o.dump = true;
    else if (arg == "--jit")
      flag(), o.jit = true;
    else if (arg == "--why")
      o.why.emplace_back(value());
    else if (arg == "--time-per-rule")
      o.timePerRule = parseTime("--time-per-rule", value());
    else if (arg == "--palette") {
      const std::string_view v = value();
      if (v != "visiblesim" && v != "lm")
        throw UsageError("--palette wants visiblesim or lm, got '" + std::string(v) + "'");
      o.paletteLm = v == "lm";
    } else if (arg == "-I")
      o.includeDirs.emplace_back(value());
    else if (arg == "--target")
      o.target = value();
    else if (arg == "--until")
      o.until = parseTime("--until", value());
    else if (arg == "--seed")
      o.seed = parseCount("--seed", value());
    else if (arg == "--fes") {
      const std::string_view name = value();
      const auto kind = simcore::parseFesKind(name);
      if (!kind) throw UsageError("--fes is heap, calendar or ladder, got '" + std::string(name) + "'");
      o.fes = *kind;
    } else if (arg == "--link-rate")
      o.linkRate = parseNumber("--link-rate", value(), true, 1e15, "a positive number of bit/s like 1e6");
    else if (arg == "--link-latency")
      o.linkLatency = parseTime("--link-latency", value());
    else if (arg == "--link-jitter")
      o.linkJitter = parseTime("--link-jitter", value());
    else if (arg == "--motion-time")
      o.motionTime = parseTime("--motion-time", value());
    else if (arg == "--tap")
      parseTaps(value(), o.taps);
    else if (arg == "--json")
      o.jsonFile = value();
    else if (arg == "--export")
      o.exportFile = value();
    else if (arg == "--export-gltf") {
      o.gltfFile = value();
      if (o.gltfFile.empty() || o.gltfFile == "-")
        throw UsageError("--export-gltf needs a file name (the glTF file is binary)");
    } else if (arg == "--mobiles-csv") {
      o.mobilesCsv = value();
      if (o.mobilesCsv.empty()) throw UsageError("--mobiles-csv needs a file name");
    } else if (arg == "--physics-step") {
      o.physicsStep = parseTime("--physics-step", value());
      if (o.physicsStep <= 0) throw UsageError("--physics-step must be longer than 0");
    } else if (arg == "--check-stability") {
      o.checkStability = true;
    } else if (arg == "--refuse-unstable") {
      o.checkStability = o.refuseUnstable = true;
    } else if (arg == "--trace") {
      o.traceFilter = simcore::parseTraceFilter(value());  // TraceFilterError: a usage error too
      o.trace = true;
    } else if (arg == "--trace-format") {
      const std::string_view name = value();
      const auto format = simcore::parseTraceFormat(name);
      if (!format) throw UsageError("--trace-format is text or json, got '" + std::string(name) + "'");
      o.traceFormat = *format;
      traceFormatOrFile = true;
    } else if (arg == "--trace-file") {
      o.traceFile = value();
      if (o.traceFile.empty()) throw UsageError("--trace-file needs a file name");
      traceFormatOrFile = true;
    } else if (arg.size() > 1 && arg[0] == '-' && arg != "-") {
      throw UsageError("unknown option '" + std::string(argv[i]) + "' (see vsim --help)");
    } else if (o.world.empty()) {
      o.world = arg;
    } else {
      throw UsageError("one world file only: got '" + o.world + "' and '" + std::string(arg) + "'");
    }
  }
  if (o.help || o.version) return o;
  checkMulticoreOptions(o, multicoreOption);
  if (o.world.empty() && worldRequired && !o.isMulticore())
    throw UsageError("no world file given (usage: vsim WORLD.xml --code LIB.so; see --help)");
  if (!o.program.empty() && !o.code.empty()) throw UsageError("give --code or --program, not both");
  if (traceFormatOrFile) o.trace = true;
  if (int(o.jsonFile == "-") + int(o.exportFile == "-") + int(o.mobilesCsv == "-") > 1)
    throw UsageError("--json, --export and --mobiles-csv cannot share stdout");
  return o;
}

}  // namespace vsim
