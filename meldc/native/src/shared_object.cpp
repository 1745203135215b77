// `meldc --emit=native`: the program's native module plus its description (native_abi.h), emitted
// as an object file and linked into a shared object by the system linker. The generated code
// calls nothing outside itself (the VM's helpers come as a table at run time), so `ld -shared`
// links it without any library.
#include <llvm/IR/Constants.h>
#include <llvm/IR/GlobalVariable.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/FileSystem.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include "meldc/native.hpp"
#include "meldvm/bytecode.hpp"
#include "native_module.hpp"

extern char** environ;

namespace meldc::native {

namespace {

// meld_native_program(): returns a constant meld_native_program_desc.
void addDescription(llvm::Module& m, const meldvm::Program& program) {
  llvm::LLVMContext& c = m.getContext();
  llvm::Type* i32 = llvm::Type::getInt32Ty(c);
  llvm::Type* i64 = llvm::Type::getInt64Ty(c);
  llvm::PointerType* ptr = llvm::PointerType::getUnqual(c);
  const std::vector<std::uint8_t> bytes = meldvm::writeBytecode(program);
  auto* bytecode = new llvm::GlobalVariable(
      m, llvm::ArrayType::get(llvm::Type::getInt8Ty(c), bytes.size()), true,
      llvm::GlobalValue::PrivateLinkage, llvm::ConstantDataArray::get(c, llvm::ArrayRef<std::uint8_t>(bytes)),
      "meld_bytecode");
  const std::size_t count = meldvm::nativeCodeBlocks(program).size();
  std::vector<llvm::Constant*> entries;
  for (std::size_t k = 0; k < count; ++k) entries.push_back(m.getFunction(blockSymbol(k)));
  auto* blocksType = llvm::ArrayType::get(ptr, count);
  auto* blocks = new llvm::GlobalVariable(m, blocksType, true, llvm::GlobalValue::PrivateLinkage,
                                          llvm::ConstantArray::get(blocksType, entries), "meld_blocks");
  auto* descType = llvm::StructType::get(c, {i32, i32, i32, i32, ptr, i64, ptr});
  llvm::Constant* desc = llvm::ConstantStruct::get(
      descType,
      {llvm::ConstantInt::get(i32, MELD_NATIVE_MAGIC), llvm::ConstantInt::get(i32, MELD_NATIVE_ABI_VERSION),
       llvm::ConstantInt::get(i32, meldvm::kBytecodeVersion), llvm::ConstantInt::get(i32, count), bytecode,
       llvm::ConstantInt::get(i64, bytes.size()), blocks});
  auto* descVar = new llvm::GlobalVariable(m, descType, true, llvm::GlobalValue::PrivateLinkage, desc,
                                           "meld_description");
  auto* entry = llvm::Function::Create(llvm::FunctionType::get(ptr, false), llvm::Function::ExternalLinkage,
                                       MELD_NATIVE_ENTRY, m);
  llvm::IRBuilder<> b(llvm::BasicBlock::Create(c, "entry", entry));
  b.CreateRet(descVar);
}

void emitObject(llvm::Module& m, llvm::TargetMachine& target, const std::string& path) {
  std::error_code ec;
  llvm::raw_fd_ostream out(path, ec, llvm::sys::fs::OF_None);
  if (ec) throw NativeError("cannot write '" + path + "': " + ec.message());
  llvm::legacy::PassManager passes;
  if (target.addPassesToEmitFile(passes, out, nullptr, llvm::CodeGenFileType::ObjectFile))
    throw NativeError("the LLVM target cannot emit object files");
  passes.run(m);
  out.flush();
  if (out.has_error()) throw NativeError("cannot write '" + path + "'");
}

// Runs `ld -shared -o OUT OBJECT` (no shell); throws with what went wrong.
void link(const std::string& object, const std::string& out) {
  const char* linker = std::getenv("MELD_LD");
  std::string ld = linker && *linker ? linker : "ld";
  std::vector<std::string> args = {ld, "-shared", "--hash-style=gnu", "-o", out, object};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, ld.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw NativeError("cannot run the linker '" + ld + "' (install binutils, or set MELD_LD)");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw NativeError("lost the linker '" + ld + "'");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw NativeError("the linker '" + ld + "' failed to write '" + out + "'");
}

}  // namespace

void writeSharedObject(const meldvm::Program& program, const std::string& path, const std::string& cpu) {
  llvm::LLVMContext context;
  std::unique_ptr<llvm::TargetMachine> target = targetMachine(cpu);
  std::unique_ptr<llvm::Module> module = buildModule(program, context, *target);
  addDescription(*module, program);
  const std::string object = path + ".o.tmp";
  try {
    emitObject(*module, *target, object);
    link(object, path);
  } catch (...) {
    std::remove(object.c_str());
    throw;
  }
  std::remove(object.c_str());
}

}  // namespace meldc::native
