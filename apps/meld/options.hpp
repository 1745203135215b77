// Command line of `meld`: run a Meld program on its own graph (spec §6) and print its database.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meldapp {

enum ExitCode {
  kExitOk = 0,
  kExitCompileErrors = 1,
  kExitUsage = 2,
  kExitBadBytecode = 3,
  kExitRuntimeError = 4,
  kExitNoSuchFact = 5,  // --why names a fact the run did not derive
};

struct Options {
  std::string program;  // FILE.meld (compiled in memory) or FILE.mbc
  bool dump = false;
  bool stats = false;
  bool help = false;
  bool version = false;
  std::vector<std::string> includeDirs;                      // -I (for .meld)
  std::vector<std::pair<std::string, std::string>> defines;  // -D NAME=VALUE (for .meld)
  std::vector<std::string> programArgs;                      // after `--`: @arg1 ...
  std::uint64_t seed = 0;        // --seed: the random stream of randint & co. (0: the default one)
  std::uint64_t maxSteps = 0;    // --max-steps: rule and process runs allowed (0: no limit)
  std::vector<std::string> why;  // --why FACT: print its derivation tree after the run
  unsigned threads = 1;          // -j N / --threads N: worker threads (1: the serial VM)
  std::string profile;           // --profile FILE.json: the threads' timelines (Chrome trace)
  bool noScheduling = false;     // --no-scheduling: coordination instructions do nothing
  bool jit = false;              // --jit: compile the rules to native code in memory first
};

std::optional<Options> parseOptions(const std::vector<std::string>& args, std::string& error);
const char* usageText();

}  // namespace meldapp
