#include "options.hpp"

#include <charconv>
#include <string>

namespace meldapp {

const char* usageText() {
  return "usage: meld FILE.meld|FILE.mbc|FILE.so [options] [-- ARGS...]\n"
         "Runs a Meld program on its own graph of nodes until quiescence (or stop-program).\n"
         "A .meld file is compiled in memory first; a .mbc file is loaded and verified; a .so\n"
         "file (meldc --emit=native) runs its native code, its bytecode verified like a .mbc.\n"
         "\n"
         "options:\n"
         "  --dump          print every node's final facts (the format of the established VM's -d)\n"
         "  -j N, --threads N\n"
         "                  run on N worker threads (default 1, the serial VM): each thread owns\n"
         "                  a contiguous range of the nodes and a thread node (§6.12); the dump\n"
         "                  is the serial one for programs whose result does not depend on the\n"
         "                  order nodes run in (thread nodes and created node ids differ)\n"
         "  --profile FILE.json\n"
         "                  write each thread's timeline as a Chrome trace-event file (open it\n"
         "                  in Perfetto or chrome://tracing): node runs, idle time, facts\n"
         "                  derived, queued nodes; runs the threaded VM, also with -j 1\n"
         "  --jit           compile the program's rules, persistent rules and functions to\n"
         "                  native code in memory (LLVM, O2) and run that: the same results as\n"
         "                  the bytecode; the compile time counts in --stats' load time\n"
         "  --stats         print facts derived/consumed/sent, rules fired, facts tried (looked\n"
         "                  at by rules, matching or not), wall time, peak memory and the\n"
         "                  VM's memory by part on standard error; with -j, a table per\n"
         "                  thread too\n"
         "  --no-scheduling ignore set-priority, add-priority, remove-priority,\n"
         "                  set-default-priority, set-static, set-moving, set-cpu, set-affinity\n"
         "                  and stop-program, as the established VM's -n does (its test suite\n"
         "                  runs some programs so)\n"
         "  -I DIR          include directory (for .meld input)\n"
         "  -D NAME=VALUE   define the constant NAME (for .meld input)\n"
         "  --seed S        seed of the random stream of randint, degeneratevector and [:random]\n"
         "                  (a non-negative integer; the same seed gives the same run)\n"
         "  --max-steps N   stop with a run-time error after N steps: rule, persistent-rule\n"
         "                  and loop runs, linear facts derived, nodes created (for programs\n"
         "                  that may not terminate; default: no limit; with -j, per thread)\n"
         "  --why FACT      after the run, print why FACT exists, like --why 'reach(@3, 3)' (the\n"
         "                  node first, the values as --dump prints them): the rule that derived\n"
         "                  it (FILE:LINE, the node it ran at) and the facts it matched, down to\n"
         "                  the axioms (FILE:LINE); repeatable. Records derivations during the run\n"
         "                  (serial runs only)\n"
         "  -- ARGS         program arguments, read by @arg1, @arg2, ...\n"
         "  --help          this text\n"
         "  --version       print the version\n"
         "\n"
         "exit status: 0 done, 1 compile errors, 2 bad command line, 3 bad bytecode,\n"
         "4 run-time error, 5 a --why fact that the run did not derive\n";
}

std::optional<Options> parseOptions(const std::vector<std::string>& args, std::string& error) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const char* what) -> std::optional<std::string> {
      if (a.size() > 2 && a[0] == '-' && a[1] != '-') return a.substr(2);  // -Idir
      if (i + 1 >= args.size()) {
        error = std::string("option '") + a + "' needs " + what;
        return std::nullopt;
      }
      return args[++i];
    };
    if (a == "--") {
      o.programArgs.assign(args.begin() + std::ptrdiff_t(i) + 1, args.end());
      break;
    } else if (a == "--dump" || a == "-d") {
      o.dump = true;
    } else if (a == "--stats") {
      o.stats = true;
    } else if (a == "--jit") {
      o.jit = true;
    } else if (a == "--no-scheduling") {
      o.noScheduling = true;
    } else if (a == "--why") {
      auto v = value("a fact like 'reach(@3, 3)'");
      if (!v) return std::nullopt;
      o.why.push_back(*v);
    } else if (a == "--threads" || a.rfind("-j", 0) == 0) {
      auto v = value("a thread count");
      if (!v) return std::nullopt;
      unsigned n = 0;
      const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
      if (v->empty() || ec != std::errc() || end != v->data() + v->size() || n < 1 || n > 1024) {
        error = "-j/--threads expects a thread count from 1 to 1024, got '" + *v + "'";
        return std::nullopt;
      }
      o.threads = n;
    } else if (a == "--profile") {
      auto v = value("a file name");
      if (!v) return std::nullopt;
      o.profile = *v;
    } else if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "--seed" || a == "--max-steps") {
      auto v = value("a non-negative integer");
      if (!v) return std::nullopt;
      std::uint64_t n = 0;
      const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
      if (v->empty() || ec != std::errc() || end != v->data() + v->size()) {
        error = a + " expects a non-negative integer, got '" + *v + "'";
        return std::nullopt;
      }
      (a == "--seed" ? o.seed : o.maxSteps) = n;
    } else if (a.rfind("-I", 0) == 0) {
      auto v = value("a directory");
      if (!v) return std::nullopt;
      o.includeDirs.push_back(*v);
    } else if (a.rfind("-D", 0) == 0) {
      auto v = value("NAME=VALUE");
      if (!v) return std::nullopt;
      const std::size_t eq = v->find('=');
      if (eq == std::string::npos || eq == 0) {
        error = "-D expects NAME=VALUE, got '" + *v + "'";
        return std::nullopt;
      }
      o.defines.emplace_back(v->substr(0, eq), v->substr(eq + 1));
    } else if (!a.empty() && a[0] == '-') {
      error = "unknown option '" + a + "'";
      return std::nullopt;
    } else if (o.program.empty()) {
      o.program = a;
    } else {
      error = "more than one program given ('" + o.program + "' and '" + a +
              "'); program arguments go after `--`";
      return std::nullopt;
    }
  }
  if (!o.help && !o.version && o.program.empty()) {
    error = "no program given";
    return std::nullopt;
  }
  if ((o.threads > 1 || !o.profile.empty()) && !o.why.empty()) {
    error = "--why records derivations in serial runs only: drop -j and --profile";
    return std::nullopt;
  }
  return o;
}

}  // namespace meldapp
