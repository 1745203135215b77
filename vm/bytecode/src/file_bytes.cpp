#include "file_bytes.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "meldvm/bytecode.hpp"

#if defined(__unix__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace meldvm::detail {

FileBytes::FileBytes(const std::string& path) {
#if defined(__unix__)
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw BytecodeError("cannot open " + path, 0);
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    void* m = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (m != MAP_FAILED) {
      ::close(fd);
      mapping_ = m;
      data_ = static_cast<const std::uint8_t*>(m);
      size_ = std::size_t(st.st_size);
      return;
    }
  }
  // From the descriptor already open: a pipe opened a second time would have lost what its
  // writer wrote meanwhile, and might wait forever for a writer that has gone.
  try {
    readDescriptor(fd, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
#else
  readStream(path);
#endif
}

FileBytes::~FileBytes() {
#if defined(__unix__)
  if (mapping_) ::munmap(mapping_, size_);
#endif
}

#if defined(__unix__)
void FileBytes::readDescriptor(int fd, const std::string& path) {
  constexpr std::size_t kBlock = 256 * 1024;
  for (std::size_t got = 0;;) {
    read_.resize(got + kBlock);
    const ssize_t n = ::read(fd, read_.data() + got, kBlock);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw BytecodeError("cannot read " + path + ": " + std::strerror(errno), 0);
    got += std::size_t(n);
    if (n == 0) {
      read_.resize(got);
      break;
    }
  }
  data_ = read_.data();
  size_ = read_.size();
}
#endif

#if !defined(__unix__)
// In blocks, not byte by byte through a stream iterator (16 instructions a byte). libstdc++
// reports some read errors (e.g. the path is a directory) by throwing from the stream buffer even
// without exceptions() set.
void FileBytes::readStream(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BytecodeError("cannot open " + path, 0);
  try {
    constexpr std::size_t kBlock = 256 * 1024;
    for (std::size_t got = 0;; got += std::size_t(in.gcount())) {
      read_.resize(got + kBlock);
      in.read(reinterpret_cast<char*>(read_.data() + got), kBlock);
      if (std::size_t(in.gcount()) < kBlock) {
        read_.resize(got + std::size_t(in.gcount()));
        break;
      }
    }
  } catch (const std::exception& e) {
    throw BytecodeError("cannot read " + path + ": " + e.what(), 0);
  }
  if (in.bad()) throw BytecodeError("cannot read " + path, 0);
  data_ = read_.data();
  size_ = read_.size();
}
#endif

}  // namespace meldvm::detail
