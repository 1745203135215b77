// The bytes of a file, for the bytecode reader: a regular file is mapped (its pages come straight
// from the page cache, many per fault), anything else (a pipe, /dev/stdin) is read in blocks from
// the same descriptor (POSIX, as the rest of the VM: dlopen, mmap).
//
// Why: reading pagerank-movies' 1.9 MB `.mbc` into a growing vector zeroed, copied and faulted in
// about 2.5 times its size; that was a quarter of the run's page faults. readBytecodeFile keeps
// the mapping as long as the program, whose literal axioms are read from it (LiteralAxioms). So a
// file changed in place during the run is read changed, and one truncated ends the run with
// SIGBUS, as a shared object's would: meldc replaces its output instead (a new file renamed over
// the old one, which a running VM keeps), as linkers do.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace meldvm::detail {

class FileBytes {
 public:
  // Throws BytecodeError (offset 0) when the file cannot be opened or read.
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  void readDescriptor(int fd, const std::string& path);  // to its end (a pipe, a device)

  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  void* mapping_ = nullptr;  // when mapped, of size_ bytes
  std::vector<std::uint8_t> read_;
};

}  // namespace meldvm::detail
