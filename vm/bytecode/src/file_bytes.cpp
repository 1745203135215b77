#include "file_bytes.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "meldvm/bytecode.hpp"

namespace meldvm::detail {

FileBytes::FileBytes(const std::string& path) {
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
}

FileBytes::~FileBytes() {
  if (mapping_) ::munmap(mapping_, size_);
}

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

}  // namespace meldvm::detail
