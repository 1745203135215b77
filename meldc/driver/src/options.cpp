#include "meldc/options.hpp"

namespace meldc {

namespace {

bool validConstName(const std::string& name) {
  if (name.empty() || name[0] < 'a' || name[0] > 'z') return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '?' || c == '-'))
      return false;
  return true;
}

}  // namespace

const char* usageText() {
  return "usage: meldc FILE.meld [-o OUT] [-I DIR]... [--no-stdlib] [--robots] [-DNAME=VALUE]...\n"
         "             [--check | --emit=KIND] [--cpu=NAME] [-j N] [--no-progress]\n"
         "\n"
         "Compiles a Linear Meld program to bytecode for the Meld VM: parses the program, merges its\n"
         "includes, resolves names, checks it, renumbers its nodes and lowers its rules.\n"
         "\n"
         "options:\n"
         "  --check          parse and check the program; print diagnostics only\n"
         "  --emit=ast       print the parsed program (declarations, rules with body and head);\n"
         "                   node literals show their internal ids (after renumbering)\n"
         "  --emit=nodes     print the node table: one line 'INTERNAL SOURCE' per initial node,\n"
         "                   ordered by internal id (renumbering of the language reference §6.1)\n"
         "  --emit=bytecode  write bytecode (default) to OUT, by default FILE with the extension .mbc\n"
         "  --emit=asm       print a disassembly of the bytecode\n"
         "  --emit=native    write a shared object (by default FILE.so) with the program's native\n"
         "                   code and tables, for meld FILE.so and vsim --program FILE.so (needs\n"
         "                   the system linker: ld, or $MELD_LD)\n"
         "  --emit=llvm      print the native code of the rules, processes and functions as\n"
         "                   optimised LLVM IR (what meld --jit runs)\n"
         "  --cpu=NAME       the processor --emit=native and --emit=llvm compile for: generic (the\n"
         "                   default of native: the shared object runs on any machine of this\n"
         "                   architecture), native (this machine's: the default of llvm, and what\n"
         "                   meld --jit uses; may not run elsewhere) or an LLVM processor name such\n"
         "                   as x86-64-v3\n"
         "  -j N, --jobs=N   threads compiling native code (--emit=native; default: one per\n"
         "                   processor); the shared object is the same whatever N is\n"
         "  --no-progress    no progress line (shown on a terminal when native code takes longer\n"
         "                   than a second to compile)\n"
         "  -o OUT           write the --emit output to OUT instead of standard output (bytecode:\n"
         "                   instead of FILE.mbc, native: of FILE.so); '-o -' is standard output,\n"
         "                   for bytecode too\n"
         "  -I DIR           search DIR for included files, after the including file's folder\n"
         "  --robots         node ids are block ids (for vsim --program): node literals keep their\n"
         "                   numbers and every id up to the largest exists (no renumbering, §6.1)\n"
         "  --no-stdlib      do not search the standard library folder, which comes after the -I\n"
         "                   folders: $MELD_STDLIB if set (empty: none), otherwise PREFIX/share/\n"
         "                   meld/stdlib for a meldc installed as PREFIX/bin/meldc, otherwise the\n"
         "                   stdlib/ folder of the source tree it was built from\n"
         "  -DNAME=VALUE     define the constant NAME as the Meld expression VALUE (replaces a\n"
         "                   'const NAME = ...' of the program, or adds one)\n"
         "  --help           print this help\n"
         "  --version        print the version\n"
         "\n"
         "Diagnostics go to standard error as FILE:LINE:COL: error: MESSAGE with the source line.\n"
         "exit codes: 0 success, 1 errors in the Meld program (including constructs this compiler\n"
         "does not support), 2 bad command line, 70 internal error (invalid bytecode produced).\n";
}

std::optional<Options> parseOptions(const std::vector<std::string>& args, std::string& error) {
  Options o;
  auto needValue = [&](size_t& i, const std::string& flag, std::string& out) {
    if (i + 1 >= args.size()) {
      error = "option '" + flag + "' needs a value";
      return false;
    }
    out = args[++i];
    return true;
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "--no-stdlib") {
      o.noStdlib = true;
    } else if (a == "--no-progress") {
      o.progress = false;
    } else if (a == "--robots") {
      o.robots = true;
    } else if (a == "--check") {
      o.emit = EmitKind::Check;
    } else if (a.rfind("--emit=", 0) == 0) {
      std::string kind = a.substr(7);
      if (kind == "ast")
        o.emit = EmitKind::Ast;
      else if (kind == "nodes")
        o.emit = EmitKind::Nodes;
      else if (kind == "bytecode")
        o.emit = EmitKind::Bytecode;
      else if (kind == "asm")
        o.emit = EmitKind::Asm;
      else if (kind == "native")
        o.emit = EmitKind::Native;
      else if (kind == "llvm")
        o.emit = EmitKind::Llvm;
      else {
        error = "unknown --emit kind '" + kind + "' (expected ast, nodes, bytecode, native, asm or llvm)";
        return std::nullopt;
      }
    } else if (a.rfind("--cpu=", 0) == 0) {
      o.cpu = a.substr(6);
      if (o.cpu.empty()) {
        error = "option '--cpu=' needs a processor name (generic, native, or an LLVM name)";
        return std::nullopt;
      }
    } else if (a.rfind("-j", 0) == 0 || a.rfind("--jobs=", 0) == 0) {  // -j N, -jN, --jobs=N
      std::string n = a[1] == 'j' ? a.substr(2) : a.substr(7);
      if (a == "-j" && !needValue(i, a, n)) return std::nullopt;
      if (n.empty() || n.size() > 4 || n.find_first_not_of("0123456789") != std::string::npos ||
          std::stoi(n) < 1) {
        error = "option '" + a + "' needs a number of threads from 1 to 9999";
        return std::nullopt;
      }
      o.jobs = static_cast<unsigned>(std::stoi(n));
    } else if (a == "-o") {
      if (!needValue(i, a, o.output)) return std::nullopt;
    } else if (a == "-I" || (a.rfind("-I", 0) == 0 && a.size() > 2)) {
      std::string dir = a.substr(2);
      if (dir.empty() && !needValue(i, a, dir)) return std::nullopt;
      o.includeDirs.push_back(dir);
    } else if (a == "-D" || (a.rfind("-D", 0) == 0 && a.size() > 2)) {
      std::string def = a.substr(2);
      if (def.empty() && !needValue(i, a, def)) return std::nullopt;
      size_t eq = def.find('=');
      if (eq == std::string::npos || !validConstName(def.substr(0, eq)) || eq + 1 == def.size()) {
        error = "bad definition '" + def + "' (expected -DNAME=VALUE with a lower-case NAME)";
        return std::nullopt;
      }
      o.defines.emplace_back(def.substr(0, eq), def.substr(eq + 1));
    } else if (a.size() > 1 && a[0] == '-') {
      error = "unknown option '" + a + "'";
      return std::nullopt;
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      error = "more than one input file ('" + o.input + "' and '" + a + "')";
      return std::nullopt;
    }
  }
  if (o.input.empty() && !o.help && !o.version) {
    error = "no input file";
    return std::nullopt;
  }
  return o;
}

}  // namespace meldc
