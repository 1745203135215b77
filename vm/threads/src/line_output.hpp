// write-string output of several threads into one stream: each thread writes into its own
// buffer, and a finished line goes to the shared stream under a lock, so lines never mix.
#pragma once

#include <mutex>
#include <ostream>
#include <streambuf>
#include <string>

namespace meldvm::threads {

class LineOutput : public std::streambuf {
 public:
  LineOutput(std::ostream& target, std::mutex& lock) : target_(target), lock_(lock) {}
  ~LineOutput() override { flushLine(); }

 protected:
  int_type overflow(int_type c) override {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    line_.push_back(char(c));
    if (c == '\n') flushLine();
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) overflow(traits_type::to_int_type(s[i]));
    return n;
  }
  int sync() override {
    flushLine();
    return 0;
  }

 private:
  void flushLine() {
    if (line_.empty()) return;
    std::lock_guard<std::mutex> guard(lock_);
    target_.write(line_.data(), std::streamsize(line_.size()));
    line_.clear();
  }
  std::ostream& target_;
  std::mutex& lock_;
  std::string line_;
};

}  // namespace meldvm::threads
