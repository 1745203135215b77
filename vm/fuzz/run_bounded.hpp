// What the fuzz entry points do with a program that loaded or compiled: run it on its own graph to
// an end — quiescence, a RuntimeError, or the step limit (a valid program may derive forever:
// bounded here, not a hang) — and dump its database, or say which run-time error ended it. With
// `native`, the blocks that have native code run it (the same text is expected).
#pragma once

#include <ostream>

#include "meldvm/machine.hpp"

namespace meldfuzz {

inline void runBounded(const meldvm::Program& program, std::ostream& out,
                       const meldvm::NativeCode* native = nullptr) {
  meldvm::MachineOptions options;
  options.maxSteps = 2000;
  options.output = &out;
  options.native = native;
  try {
    meldvm::Machine machine(program, options);
    machine.run();
    machine.dump(out);
  } catch (const meldvm::RuntimeError& e) {
    out << "run-time error: " << e.what() << '\n';
  }
}

}  // namespace meldfuzz
