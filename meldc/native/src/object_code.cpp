// Object code for a program's partitions (native_module.hpp), compiled on several threads: each
// thread takes the next partition and builds it in its own LLVMContext with its own target machine
// (neither may be shared between threads), so a large program compiles about as many times faster
// as there are processors, and only the partitions in flight are in memory as IR.
#include <llvm/ADT/SmallVector.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "native_module.hpp"

namespace meldc::native {

namespace {

llvm::SmallVector<char, 0> emitObject(llvm::Module& module, llvm::TargetMachine& target) {
  llvm::SmallVector<char, 0> object;
  llvm::raw_svector_ostream out(object);
  llvm::legacy::PassManager passes;
  if (target.addPassesToEmitFile(passes, out, nullptr, llvm::CodeGenFileType::ObjectFile))
    throw NativeError("the LLVM target cannot emit object files");
  passes.run(module);
  return object;
}

}  // namespace

std::vector<llvm::SmallVector<char, 0>> compileObjects(const meldvm::Program& program, const std::string& cpu,
                                                       unsigned jobs, const ModuleFinisher& finish,
                                                       const CompileProgress& progress) {
  const std::vector<const meldvm::CodeBlock*> blocks = meldvm::nativeCodeBlocks(program);
  const std::vector<BlockRange> ranges = partitionBlocks(blocks);
  std::vector<llvm::SmallVector<char, 0>> objects(ranges.size());
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;  // under `lock`, as progress's calls
  std::mutex lock;
  std::exception_ptr firstError;
  auto work = [&] {
    try {
      std::unique_ptr<llvm::TargetMachine> target = targetMachine(cpu);
      for (std::size_t k = next++; k < ranges.size(); k = next++) {
        llvm::LLVMContext context;
        std::unique_ptr<llvm::Module> module = buildModule(program, blocks, context, *target, ranges[k]);
        if (finish) finish(*module, k);
        objects[k] = emitObject(*module, *target);
        const std::lock_guard<std::mutex> hold(lock);
        ++done;
        if (progress) progress(done, ranges.size());
      }
    } catch (...) {
      next = ranges.size();  // the others stop after their partition
      const std::lock_guard<std::mutex> hold(lock);
      if (!firstError) firstError = std::current_exception();
    }
  };
  if (jobs == 0) jobs = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t threads = std::min<std::size_t>(jobs, ranges.size());
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  if (firstError) std::rethrow_exception(firstError);
  return objects;
}

}  // namespace meldc::native
