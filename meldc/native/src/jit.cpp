// `meld --jit`: the program's native module compiled in this process with ORC LLJIT.
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Target/TargetMachine.h>

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

std::unique_ptr<Jit> Jit::compile(const meldvm::Program& program) {
  std::unique_ptr<llvm::TargetMachine> target = hostTargetMachine();
  auto context = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> module = buildModule(program, *context, *target);
  std::unique_ptr<Jit> out(new Jit());
  out->engine_->jit = orThrow(llvm::orc::LLJITBuilder().create(), "cannot start the JIT");
  llvm::orc::LLJIT& jit = *out->engine_->jit;
  module->setDataLayout(jit.getDataLayout());
  if (llvm::Error e = jit.addIRModule(llvm::orc::ThreadSafeModule(std::move(module), std::move(context))))
    throw NativeError("the JIT refused the module: " + llvm::toString(std::move(e)));
  const std::size_t blocks = meldvm::nativeCodeBlocks(program).size();
  out->entries_.reserve(blocks);
  for (std::size_t k = 0; k < blocks; ++k) {
    const llvm::orc::ExecutorAddr address = orThrow(jit.lookup(blockSymbol(k)), "the JIT lost a block");
    out->entries_.push_back(address.toPtr<meld_native_block>());
  }
  return out;
}

}  // namespace meldc::native
