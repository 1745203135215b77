// Command line of the `meldc` driver.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meldc {

enum class EmitKind { Bytecode, Native, Asm, Llvm, Ast, Nodes, Check };

// Exit codes of meldc.
inline constexpr int kExitOk = 0;
inline constexpr int kExitProgramErrors = 1;  // the Meld program has errors
inline constexpr int kExitUsage = 2;          // bad command line
inline constexpr int kExitInternal = 70;      // internal error: the compiler produced invalid bytecode

struct Options {
  std::string input;
  std::string output;                    // -o; empty = stdout
  std::vector<std::string> includeDirs;  // -I, in order (the driver appends the stdlib folder)
  std::vector<std::pair<std::string, std::string>> defines;  // -DNAME=VALUE
  EmitKind emit = EmitKind::Bytecode;
  bool noStdlib = false;  // --no-stdlib: do not search the standard library folder
  bool robots = false;    // --robots: node ids are block ids (no renumbering)
  std::string cpu;        // --cpu: the processor of --emit=native (default generic) / llvm (native)
  unsigned jobs = 0;      // -j: threads compiling native code (0: one per processor)
  bool progress = true;   // --no-progress: no progress line of native compiles
  bool help = false;
  bool version = false;
};

// Parses argv; on a usage error returns nullopt and sets `error`.
std::optional<Options> parseOptions(const std::vector<std::string>& args, std::string& error);

const char* usageText();

}  // namespace meldc
