// What the fuzz entry points do with a program that loaded or compiled: run it on its own graph to
// an end — quiescence, a RuntimeError, or the step limit (a valid program may derive forever:
// bounded here, not a hang) — and dump its database, or say which run-time error ended it. With
// `native`, the blocks that have native code run it (the same text is expected).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <ostream>

#include "meldvm/bytecode.hpp"
#include "meldvm/machine.hpp"

namespace meldfuzz {

// The program an input holds, or nullptr when the reader or the verifier refuses it (what they
// are for, not a bug).
inline std::unique_ptr<meldvm::Program> readOrNull(const std::uint8_t* data, std::size_t size) {
  try {
    return meldvm::readBytecode(data, size);
  } catch (const meldvm::BytecodeError&) {
    return nullptr;
  }
}

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
    // What the heap holds at the end: native code that makes or drops objects itself must count
    // them as the interpreter does.
    out << "heap: " << machine.heap().liveObjects() << " objects, " << machine.heap().bytesInUse()
        << " bytes\n";
  } catch (const meldvm::RuntimeError& e) {
    out << "run-time error: " << e.what() << '\n';
  }
}

}  // namespace meldfuzz
