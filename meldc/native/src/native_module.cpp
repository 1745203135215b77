#include "native_module.hpp"

#include <llvm/Analysis/CGSCCPassManager.h>
#include <llvm/Analysis/LoopAnalysisManager.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/IR/PassManager.h>
#include <llvm/IR/Verifier.h>
#include <llvm/MC/MCSubtargetInfo.h>
#include <llvm/MC/TargetRegistry.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>
#include <llvm/TargetParser/Host.h>

#include <mutex>

#include "lower_block.hpp"

namespace meldc::native {

std::string blockSymbol(std::size_t k) { return "meld_block_" + std::to_string(k); }

namespace {

const llvm::Target& processTarget(std::string& triple) {
  static std::once_flag initialised;  // LLVM's target registry is process-wide
  std::call_once(initialised, [] {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
  });
  triple = llvm::sys::getProcessTriple();
  std::string error;
  const llvm::Target* target = llvm::TargetRegistry::lookupTarget(triple, error);
  if (!target) throw NativeError("no LLVM target for " + triple + ": " + error);
  return *target;
}

std::string cpuName(const std::string& cpu) {
  return cpu == "native" ? llvm::sys::getHostCPUName().str() : cpu;
}

}  // namespace

bool knownCpu(const std::string& cpu) {
  std::string triple;
  const llvm::Target& target = processTarget(triple);
  const std::unique_ptr<llvm::MCSubtargetInfo> info(target.createMCSubtargetInfo(triple, "", ""));
  return cpu == "generic" || cpu == "native" || (info && info->isCPUStringValid(cpu));
}

std::unique_ptr<llvm::TargetMachine> targetMachine(const std::string& cpu) {
  if (!knownCpu(cpu)) throw NativeError("unknown processor '" + cpu + "' (try generic or native)");
  std::string triple;
  const llvm::Target& target = processTarget(triple);
  llvm::TargetOptions options;
  std::unique_ptr<llvm::TargetMachine> machine(target.createTargetMachine(
      triple, cpuName(cpu), "", options, llvm::Reloc::PIC_, std::nullopt, llvm::CodeGenOptLevel::Default));
  if (!machine) throw NativeError("cannot create an LLVM target machine for " + triple);
  return machine;
}

namespace {

// Not the O2 pipeline: the lowered code is straight-line register moves, helper calls and the
// loops' bodies, and what pays off is inlining the bodies into their loops, promoting what SROA can,
// removing redundant loads and stores (early CSE with memory SSA) and folding. O2 took three times
// as long for the same run time (callgrind: heat-transfer and n-queens within 1 %), and codegen at
// the default level does the rest (register allocation, scheduling).
constexpr const char* kPipeline = "cgscc(inline),function(sroa,early-cse<memssa>,instcombine,simplifycfg)";

void optimise(llvm::Module& module, llvm::TargetMachine& target) {
  llvm::LoopAnalysisManager loops;
  llvm::FunctionAnalysisManager functions;
  llvm::CGSCCAnalysisManager sccs;
  llvm::ModuleAnalysisManager modules;
  llvm::PassBuilder builder(&target);
  builder.registerModuleAnalyses(modules);
  builder.registerCGSCCAnalyses(sccs);
  builder.registerFunctionAnalyses(functions);
  builder.registerLoopAnalyses(loops);
  builder.crossRegisterProxies(loops, functions, sccs, modules);
  llvm::ModulePassManager passes;
  if (llvm::Error e = builder.parsePassPipeline(passes, kPipeline))
    throw NativeError("the optimisation pipeline does not parse: " + llvm::toString(std::move(e)));
  passes.run(module, modules);
}

}  // namespace

std::vector<BlockRange> partitionBlocks(const std::vector<const meldvm::CodeBlock*>& blocks) {
  // About 60 rules of B5's generated program (68 words each) per module: big enough that the
  // modules' fixed costs do not show, small enough that a large program keeps every processor busy
  // and little IR in memory.
  constexpr std::size_t kWordsPerPartition = 4096;
  std::vector<BlockRange> ranges(1);
  std::size_t words = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (words >= kWordsPerPartition) {
      ranges.push_back({k, k});
      words = 0;
    }
    ranges.back().last = k + 1;
    words += blocks[k]->code.size();
  }
  return ranges;
}

std::unique_ptr<llvm::Module> buildModule(const meldvm::Program& program,
                                          const std::vector<const meldvm::CodeBlock*>& blocks,
                                          llvm::LLVMContext& context, llvm::TargetMachine& target,
                                          BlockRange range) {
  auto module = std::make_unique<llvm::Module>("meld", context);
  module->setTargetTriple(target.getTargetTriple().str());
  module->setDataLayout(target.createDataLayout());
  NativeTypes types(*module);
  // nativeCodeBlocks' order: rules, then processes, then functions and the globals' initialiser.
  const std::size_t processesFrom = program.rules.size(),
                    processesTo = processesFrom + program.processes.size();
  for (std::size_t k = range.first; k < range.last; ++k)
    lowerBlock(types, program, *blocks[k], blockSymbol(k),
               k < processesFrom ? BlockKind::Rule
               : k < processesTo ? BlockKind::Process
                                 : BlockKind::Other);
  std::string problems;
  llvm::raw_string_ostream out(problems);
  if (llvm::verifyModule(*module, &out))
    throw NativeError("the lowered module is not valid LLVM IR: " + problems);
  optimise(*module, target);
  return module;
}

std::string llvmText(const meldvm::Program& program, const std::string& cpu) {
  llvm::LLVMContext context;
  std::unique_ptr<llvm::TargetMachine> target = targetMachine(cpu);
  const std::vector<const meldvm::CodeBlock*> blocks = meldvm::nativeCodeBlocks(program);
  std::unique_ptr<llvm::Module> module = buildModule(program, blocks, context, *target, {0, blocks.size()});
  std::string text;
  llvm::raw_string_ostream out(text);
  module->print(out, nullptr);
  return text;
}

}  // namespace meldc::native
