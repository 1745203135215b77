// The native entry points of a program's code blocks (native_abi.h), from a JIT or a loaded shared
// object: the Machine runs a block natively when it has an entry, in the interpreter otherwise.
// Shared read-only by every shard of a threaded run.
#pragma once

#include <span>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "meldvm/native_abi.h"
#include "meldvm/program.hpp"

namespace meldvm {

class NativeCode {
 public:
  // entries[k] runs native block k (nativeCodeBlocks' numbering), one entry per block.
  NativeCode(const Program& program, std::span<const meld_native_block> entries) {
    const std::vector<const CodeBlock*> blocks = nativeCodeBlocks(program);
    if (entries.size() != blocks.size()) throw std::length_error("NativeCode: one entry per native block");
    for (std::size_t k = 0; k < blocks.size(); ++k) entries_[blocks[k]] = entries[k];
  }

  meld_native_block find(const CodeBlock& block) const {
    const auto it = entries_.find(&block);
    return it == entries_.end() ? nullptr : it->second;
  }

 private:
  std::unordered_map<const CodeBlock*, meld_native_block> entries_;
};

}  // namespace meldvm
