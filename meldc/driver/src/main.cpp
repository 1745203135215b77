// meldc: the Meld compiler driver. Runs the front end, then either prints the AST / node table or
// lowers the program and writes bytecode (.mbc) or its disassembly.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "meldc/ast_dump.hpp"
#include "meldc/compile_progress_line.hpp"
#include "meldc/frontend.hpp"
#include "meldc/ground_facts.hpp"
#include "meldc/includes.hpp"
#include "meldc/lower.hpp"
#include "meldc/native.hpp"
#include "meldc/options.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/robot_program.hpp"

#ifndef MELDC_VERSION
#define MELDC_VERSION "unknown"
#endif

namespace {

bool writeDirectly(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (out) out.write(bytes.data(), std::streamsize(bytes.size()));
  return out && (out.close(), bool(out));
}

// Writes `bytes` to `path` (binary); false on failure. "-" is standard output.
// A regular file (or a new one) is written next to its place under another name, then renamed
// over it: a VM running the old file keeps reading it unchanged (meld maps a .mbc and reads a
// data file's facts from the mapping), and an interrupted write leaves the old file whole. Other
// files (a device, a pipe) are written in place.
bool writeFile(const std::string& path, const std::string& bytes) {
  if (path == "-") {
    std::cout.write(bytes.data(), std::streamsize(bytes.size()));
    return bool(std::cout.flush());
  }
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path target = path;
  if (fs::is_symlink(path, ec)) target = fs::weakly_canonical(path, ec);
  const fs::file_type type = ec ? fs::file_type::unknown : fs::status(target, ec).type();
  if (type != fs::file_type::not_found && type != fs::file_type::regular) return writeDirectly(path, bytes);
  const std::string temporary = target.string() + ".tmp" + std::to_string(getpid());
  bool written = writeDirectly(temporary, bytes);
  if (written && type == fs::file_type::regular)  // the replaced file's permissions stay
    fs::permissions(temporary, fs::status(target, ec).permissions(), ec);
  if (!written || std::rename(temporary.c_str(), target.c_str()) != 0) {
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

// FILE.meld -> FILE.mbc (FILE -> FILE.mbc when there is no extension).
// The input's path with another extension (".mbc", ".so").
std::string defaultOutputPath(const std::string& input, const char* extension) {
  const size_t slash = input.find_last_of('/');
  const size_t dot = input.find_last_of('.');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
    return input.substr(0, dot) + extension;
  return input + extension;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace meldc;
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string error;
  std::optional<Options> options = parseOptions(args, error);
  if (!options) {
    std::cerr << "meldc: error: " << error << "\n(run 'meldc --help' for usage)\n";
    return kExitUsage;
  }
  if (options->help) {
    std::cout << usageText();
    return kExitOk;
  }
  if (options->version) {
    std::cout << "meldc " << MELDC_VERSION << " (bytecode version " << meldvm::kBytecodeVersion << ")\n";
    return kExitOk;
  }

  SourceManager sources;
  Diagnostics diag(sources, std::cerr);
  if (options->emit == EmitKind::Bytecode && options->output == "-" && isatty(STDOUT_FILENO)) {
    std::cerr << "meldc: error: -o -: refusing to write bytecode to a terminal (redirect it, or "
                 "use --emit=asm to read it)\n";
    return kExitUsage;
  }
  if (options->cpu.empty()) options->cpu = options->emit == EmitKind::Llvm ? "native" : "generic";
  if ((options->emit == EmitKind::Native || options->emit == EmitKind::Llvm) &&
      !meldc::native::knownCpu(options->cpu)) {
    std::cerr << "meldc: error: unknown processor '" << options->cpu
              << "' for --cpu (generic, native, or an LLVM processor name such as x86-64-v3)\n";
    return kExitUsage;
  }
  FrontEndInput input{options->input, options->includeDirs, options->defines};
  // After the -I folders, so that a program's own copy of a target file wins.
  if (!options->noStdlib && !defaultStdlibDir().empty()) input.includeDirs.push_back(defaultStdlibDir());
  input.identityNodes = options->robots;
  std::optional<ast::Program> program = runFrontEnd(input, sources, diag);
  if (!program) return kExitProgramErrors;
  if (options->emit == EmitKind::Check) return kExitOk;

  std::ostringstream text;
  if (options->emit == EmitKind::Ast) {
    materializeGroundFacts(*program, sources);  // the dump shows every fact as a statement
    dumpProgram(*program, sources, text);
  } else if (options->emit == EmitKind::Nodes) {
    for (const ast::NodeId& n : program->nodeTable) text << n.internal << ' ' << n.source << '\n';
  } else {
    std::unique_ptr<meldvm::Program> lowered = lowerProgram(*program, sources, diag);
    if (!lowered) return kExitProgramErrors;
    try {
      meldvm::verifyProgram(*lowered);
    } catch (const meldvm::BytecodeError& e) {
      std::cerr << "meldc: internal error: the compiler produced invalid bytecode: " << e.what() << '\n';
      return kExitInternal;
    }
    if (options->robots) {  // the check vsim makes when it loads the program
      try {
        meldvm::checkRobotProgram(*lowered);
      } catch (const meldvm::BlockProgramError& e) {
        std::cerr << options->input << ": error: " << e.what() << '\n';
        return kExitProgramErrors;
      }
    }
    if (options->emit == EmitKind::Asm) {
      meldvm::disassemble(*lowered, text);
    } else if (options->emit == EmitKind::Native) {
      const std::string path =
          options->output.empty() ? defaultOutputPath(options->input, ".so") : options->output;
      if (path == "-") {
        std::cerr << "meldc: error: a shared object cannot go to standard output (-o -)\n";
        return kExitUsage;
      }
      try {
        CompileProgressLine progress("meldc", options->progress && isatty(STDERR_FILENO));
        meldc::native::writeSharedObject(
            *lowered, path, options->cpu, options->jobs,
            [&](std::size_t done, std::size_t total) { progress.update(done, total); });
      } catch (const meldc::native::NativeError& e) {
        std::cerr << "meldc: error: " << e.what() << '\n';
        return kExitProgramErrors;
      }
      return kExitOk;
    } else if (options->emit == EmitKind::Llvm) {
      try {
        text << meldc::native::llvmText(*lowered, options->cpu);
      } catch (const meldc::native::NativeError& e) {
        std::cerr << "meldc: internal error: native code: " << e.what() << '\n';
        return kExitInternal;
      }
    } else {
      const std::vector<std::uint8_t> bytes = meldvm::writeBytecode(*lowered);
      const std::string path =
          options->output.empty() ? defaultOutputPath(options->input, ".mbc") : options->output;
      if (!writeFile(path, std::string(bytes.begin(), bytes.end()))) {
        std::cerr << "meldc: error: cannot write '" << path << "'\n";
        return kExitProgramErrors;
      }
      return kExitOk;
    }
  }
  if (options->output.empty()) {
    std::cout << text.str();
  } else if (!writeFile(options->output, text.str())) {
    std::cerr << "meldc: error: cannot write '" << options->output << "'\n";
    return kExitProgramErrors;
  }
  return kExitOk;
}
