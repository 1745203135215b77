// The console's lines on their way from the kernel thread to the GUI: a bounded queue under a
// mutex, fed by an ostream (the Meld program's output, the trace observer) that cuts lines.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

namespace ide {

class ConsoleBuffer {
 public:
  explicit ConsoleBuffer(std::size_t maxLines = 20000) : maxLines_(maxLines) {}
  void push(std::string line);
  // The lines pushed since the last call; when lines were dropped, a first line says how many.
  std::vector<std::string> take();

 private:
  std::mutex mutex_;
  std::deque<std::string> lines_;
  std::size_t maxLines_;
  std::uint64_t dropped_ = 0;
};

// An ostream whose complete lines go to a ConsoleBuffer (used on one thread only).
class ConsoleStream : public std::ostream {
 public:
  explicit ConsoleStream(ConsoleBuffer& sink) : std::ostream(&buf_), buf_(sink) {}
  ~ConsoleStream() override;

 private:
  class LineBuf : public std::streambuf {
   public:
    explicit LineBuf(ConsoleBuffer& sink) : sink_(sink) {}
    void flushPartial();

   protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;

   private:
    ConsoleBuffer& sink_;
    std::string pending_;
  };
  LineBuf buf_;
};

}  // namespace ide
