// `meld --jit`: the program's native code compiled in this process (object code of each partition,
// compiled on several threads, as for a shared object) and linked into it by ORC LLJIT.
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/RTDyldObjectLinkingLayer.h>
#include <llvm/ExecutionEngine/SectionMemoryManager.h>
#include <llvm/Support/SmallVectorMemoryBuffer.h>

#include "meldc/native.hpp"
#include "native_module.hpp"

namespace meldc::native {

struct Jit::Engine {
  std::unique_ptr<llvm::orc::LLJIT> jit;
};

Jit::Jit() : engine_(std::make_unique<Engine>()) {}
Jit::~Jit() = default;

namespace {
template <class T>
T orThrow(llvm::Expected<T> value, const char* what) {
  if (!value) throw NativeError(std::string(what) + ": " + llvm::toString(value.takeError()));
  return std::move(*value);
}
}  // namespace

std::unique_ptr<Jit> Jit::compile(const meldvm::Program& program, const CompileProgress& progress) {
  std::vector<llvm::SmallVector<char, 0>> objects = compileObjects(program, "native", 0, {}, progress);
  std::unique_ptr<Jit> out(new Jit());
  // RuntimeDyld links the object, not JITLink: JITLink 19 took time and memory that grew faster
  // than the program (a 2,000-rule program: 0.5 GB; 10,000 rules: past 15 GB), RuntimeDyld grows
  // with it. Its memory manager registers the unwind tables, so errors still unwind.
  auto linker = [](llvm::orc::ExecutionSession& session,
                   const llvm::Triple&) -> llvm::Expected<std::unique_ptr<llvm::orc::ObjectLayer>> {
    return std::make_unique<llvm::orc::RTDyldObjectLinkingLayer>(
        session, [] { return std::make_unique<llvm::SectionMemoryManager>(); });
  };
  out->engine_->jit = orThrow(llvm::orc::LLJITBuilder().setObjectLinkingLayerCreator(linker).create(),
                              "cannot start the JIT");
  llvm::orc::LLJIT& jit = *out->engine_->jit;
  for (llvm::SmallVector<char, 0>& object : objects) {
    auto buffer = std::make_unique<llvm::SmallVectorMemoryBuffer>(std::move(object), "meld-native.o", false);
    if (llvm::Error e = jit.addObjectFile(std::move(buffer)))
      throw NativeError("the JIT refused the object code: " + llvm::toString(std::move(e)));
  }
  const std::size_t blocks = meldvm::nativeCodeBlocks(program).size();
  out->entries_.reserve(blocks);
  for (std::size_t k = 0; k < blocks; ++k) {
    const llvm::orc::ExecutorAddr address = orThrow(jit.lookup(blockSymbol(k)), "the JIT lost a block");
    out->entries_.push_back(address.toPtr<meld_native_block>());
  }
  return out;
}

}  // namespace meldc::native
