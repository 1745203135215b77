// `meldc --emit=native`: the program's native code (one object file per partition, compiled on
// several threads) plus its description (native_abi.h, in the first partition's object), linked into
// a shared object by the system linker. The generated code calls nothing outside itself (the VM's
// helpers come as a table at run time), so `ld -shared` links it without any library.
#include <llvm/IR/Constants.h>
#include <llvm/IR/GlobalVariable.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/LLVMContext.h>
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

#include "lower_block.hpp"
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
  bytecode->setAlignment(llvm::Align(8));  // so that the VM reads its words in place
  const std::size_t count = meldvm::nativeCodeBlocks(program).size();
  std::vector<llvm::Constant*> entries;
  for (std::size_t k = 0; k < count; ++k)  // blocks of the other partitions are declared here
    entries.push_back(
        llvm::cast<llvm::Constant>(m.getOrInsertFunction(blockSymbol(k), blockFunctionType(c)).getCallee()));
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

void writeFile(const llvm::SmallVector<char, 0>& bytes, const std::string& path) {
  std::error_code ec;
  llvm::raw_fd_ostream out(path, ec, llvm::sys::fs::OF_None);
  if (ec) throw NativeError("cannot write '" + path + "': " + ec.message());
  out.write(bytes.data(), bytes.size());
  out.flush();
  if (out.has_error()) throw NativeError("cannot write '" + path + "'");
}

// Runs `ld -shared -o OUT OBJECTS...` (no shell); throws with what went wrong.
void link(const std::vector<std::string>& objects, const std::string& out) {
  const char* linker = std::getenv("MELD_LD");
  std::string ld = linker && *linker ? linker : "ld";
  // --eh-frame-hdr: the unwinder finds a shared object's unwind tables through PT_GNU_EH_FRAME;
  // without it a run-time error thrown by a helper cannot unwind through the native code.
  std::vector<std::string> args = {ld, "-shared", "--hash-style=gnu", "--eh-frame-hdr", "-o", out};
  args.insert(args.end(), objects.begin(), objects.end());
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

void writeSharedObject(const meldvm::Program& program, const std::string& path, const std::string& cpu,
                       unsigned jobs, const CompileProgress& progress) {
  const std::vector<llvm::SmallVector<char, 0>> objects = compileObjects(
      program, cpu, jobs,
      [&](llvm::Module& module, std::size_t partition) {
        if (partition == 0) addDescription(module, program);
      },
      progress);
  std::vector<std::string> files;
  try {
    for (std::size_t k = 0; k < objects.size(); ++k) {
      files.push_back(path + "." + std::to_string(k) + ".o.tmp");
      writeFile(objects[k], files.back());
    }
    link(files, path);
  } catch (...) {
    for (const std::string& f : files) std::remove(f.c_str());
    throw;
  }
  for (const std::string& f : files) std::remove(f.c_str());
}

}  // namespace meldc::native
