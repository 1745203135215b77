// meldc: the Meld compiler driver. This slice runs the front end (parse, includes, names) and
// can print the AST; bytecode output is refused explicitly until the back end exists.
#include <fstream>
#include <iostream>

#include "meldc/ast_dump.hpp"
#include "meldc/frontend.hpp"
#include "meldc/options.hpp"

#ifndef MELDC_VERSION
#define MELDC_VERSION "unknown"
#endif

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
    std::cout << "meldc " << MELDC_VERSION << " (front end only: bytecode output not implemented yet)\n";
    return kExitOk;
  }
  if (options->emit == EmitKind::Bytecode || options->emit == EmitKind::Asm) {
    std::cerr << "meldc: error: bytecode output is not implemented yet (this meldc is the front end only; "
                 "use --check, --emit=ast or --emit=nodes)\n";
    return kExitUsage;
  }

  SourceManager sources;
  Diagnostics diag(sources, std::cerr);
  FrontEndInput input{options->input, options->includeDirs, options->defines};
  std::optional<ast::Program> program = runFrontEnd(input, sources, diag);
  if (!program) return kExitProgramErrors;

  if (options->emit == EmitKind::Ast || options->emit == EmitKind::Nodes) {
    auto write = [&](std::ostream& out) {
      if (options->emit == EmitKind::Ast)
        dumpProgram(*program, sources, out);
      else
        for (const ast::NodeId& n : program->nodeTable) out << n.internal << ' ' << n.source << '\n';
    };
    if (options->output.empty()) {
      write(std::cout);
    } else {
      std::ofstream out(options->output, std::ios::binary);
      if (out) write(out);
      if (!out || (out.close(), !out)) {
        std::cerr << "meldc: error: cannot write '" << options->output << "'\n";
        return kExitProgramErrors;
      }
    }
  }
  return kExitOk;
}
