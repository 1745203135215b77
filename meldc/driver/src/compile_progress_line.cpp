#include "meldc/compile_progress_line.hpp"

#include <cstdio>
#include <utility>

namespace meldc {

CompileProgressLine::CompileProgressLine(std::string tool, bool enabled)
    : tool_(std::move(tool)), enabled_(enabled), start_(Clock::now()), lastDraw_(start_) {}

void CompileProgressLine::update(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - start_ < std::chrono::seconds(1) || now - lastDraw_ < std::chrono::milliseconds(250)) return;
  lastDraw_ = now;
  shown_ = true;
  const double wall = std::chrono::duration<double>(now - start_).count();
  // \r and "erase to end of line": the line is redrawn in place whatever its previous length.
  std::fprintf(stderr, "\r\033[K%s: compiling native code: %zu/%zu parts (%3.0f%%)   wall %.1f s",
               tool_.c_str(), done, total, total ? 100.0 * double(done) / double(total) : 100.0, wall);
  std::fflush(stderr);
}

void CompileProgressLine::finish() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace meldc
