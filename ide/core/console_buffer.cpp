#include "console_buffer.hpp"

namespace ide {

void ConsoleBuffer::push(std::string line) {
  std::lock_guard lock(mutex_);
  lines_.push_back(std::move(line));
  while (lines_.size() > maxLines_) {
    lines_.pop_front();
    ++dropped_;
  }
}

std::vector<std::string> ConsoleBuffer::take() {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  out.reserve(lines_.size() + 1);
  if (dropped_) out.push_back("... " + std::to_string(dropped_) + " earlier lines dropped (console limit)");
  dropped_ = 0;
  for (std::string& l : lines_) out.push_back(std::move(l));
  lines_.clear();
  return out;
}

ConsoleStream::~ConsoleStream() { buf_.flushPartial(); }

void ConsoleStream::LineBuf::flushPartial() {
  if (!pending_.empty()) sink_.push(std::move(pending_));
  pending_.clear();
}

ConsoleStream::LineBuf::int_type ConsoleStream::LineBuf::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  const char ch = traits_type::to_char_type(c);
  xsputn(&ch, 1);
  return c;
}

std::streamsize ConsoleStream::LineBuf::xsputn(const char* s, std::streamsize n) {
  for (std::streamsize i = 0; i < n; ++i) {
    if (s[i] == '\n') {
      sink_.push(std::move(pending_));
      pending_.clear();
    } else {
      pending_ += s[i];
    }
  }
  return n;
}

}  // namespace ide
