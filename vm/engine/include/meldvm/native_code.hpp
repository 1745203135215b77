// The native entry points of a program's code blocks (native_abi.h), from a JIT or a loaded shared
// object: the Machine runs a block natively when it has an entry, in the interpreter otherwise.
// Shared read-only by every shard of a threaded run.
#pragma once

#include <cstddef>
#include <unordered_map>
#include <vector>

#include "meldvm/native_abi.h"
#include "meldvm/program.hpp"

namespace meldvm {

class NativeCode {
 public:
  explicit NativeCode(const Program& program) : blocks_(nativeCodeBlocks(program)) {}

  std::size_t blockCount() const { return blocks_.size(); }
  // The entry of native block `k` (nativeCodeBlocks' numbering).
  void set(std::size_t k, meld_native_block entry) { entries_[blocks_.at(k)] = entry; }
  meld_native_block find(const CodeBlock& block) const {
    const auto it = entries_.find(&block);
    return it == entries_.end() ? nullptr : it->second;
  }

 private:
  std::vector<const CodeBlock*> blocks_;
  std::unordered_map<const CodeBlock*, meld_native_block> entries_;
};

}  // namespace meldvm
