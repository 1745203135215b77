// Helpers for the back-end tests: compile a program text to a meldvm::Program (front end +
// lowering + verifyProgram) and decode code blocks into instructions.
#pragma once

#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "meldc/frontend.hpp"
#include "meldc/lower.hpp"
#include "meldvm/bytecode.hpp"
#include "meldvm/program.hpp"
#include "temp_dir.hpp"

struct Instr {
  meldvm::Opcode op;
  std::vector<std::uint32_t> operands;  // as in the code ('*', 'W': the count, then the registers or words)
  std::uint32_t at;                     // word offset
};

inline std::vector<Instr> decode(const meldvm::CodeBlock& block) {
  std::vector<Instr> out;
  const auto& code = block.code;
  for (std::size_t pc = 0; pc < code.size();) {
    Instr ins{meldvm::Opcode(code[pc]), {}, std::uint32_t(pc)};
    const std::string letters = meldvm::opcodeInfo(ins.op).operands;
    ++pc;
    for (char c : letters) {
      const std::size_t n = c == 'D' ? 2 : c == '*' || c == 'W' ? 1 + code.at(pc) : 1;
      for (std::size_t k = 0; k < n; ++k) ins.operands.push_back(code.at(pc++));
    }
    out.push_back(std::move(ins));
  }
  return out;
}

inline std::vector<Instr> only(const meldvm::CodeBlock& block, meldvm::Opcode op) {
  std::vector<Instr> out;
  for (Instr& i : decode(block))
    if (i.op == op) out.push_back(std::move(i));
  return out;
}

inline std::string opNames(const meldvm::CodeBlock& block) {
  std::string out;
  for (const Instr& i : decode(block)) {
    if (!out.empty()) out += ' ';
    out += meldvm::opcodeInfo(i.op).name;
  }
  return out;
}

struct Lowered {
  TempDir dir;
  meldc::SourceManager sources;
  std::ostringstream messages;
  meldc::Diagnostics diag{sources, messages};
  std::unique_ptr<meldvm::Program> program;
  std::string verifyError;

  explicit Lowered(const std::string& text) {
    auto ast = meldc::runFrontEnd(meldc::FrontEndInput{dir.write("t.meld", text), {}, {}}, sources, diag);
    if (!ast) return;
    program = meldc::lowerProgram(*ast, sources, diag);
    if (!program) return;
    try {
      meldvm::verifyProgram(*program);
    } catch (const meldvm::BytecodeError& e) {
      verifyError = e.what();
    }
  }
  // Compiled without errors and the result verifies.
  bool ok() const { return program && !diag.hasErrors() && verifyError.empty(); }
  std::string errors() const { return messages.str() + verifyError; }
  const meldvm::Program& p() const { return *program; }
  meldvm::PredId pred(const std::string& name) const {
    return meldvm::PredId(program->predicates.find(name));
  }
  const meldvm::CodeBlock& rule(std::size_t i) const { return program->rules.at(i).block; }
};

// ITER flags of the loops of a block, in code order.
inline std::vector<std::uint32_t> iterFlags(const meldvm::CodeBlock& block) {
  std::vector<std::uint32_t> out;
  for (const Instr& i : decode(block))
    if (i.op == meldvm::Opcode::ITER || i.op == meldvm::Opcode::ITER_SORTED ||
        i.op == meldvm::Opcode::ITER_KEY)
      out.push_back(i.operands.at(2));
  return out;
}
