// A status line redrawn in place on stderr (vsim's progress, native compiles in meldc, meld and
// vsim): it appears only after a second of wall time, so that short runs stay clean, is redrawn at
// most four times a second, and erase() clears it so that what follows starts on a clean line.
#pragma once

#include <chrono>
#include <cstdio>

namespace support {

class TerminalLine {
 public:
  // `enabled`: draw at all (callers pass whether stderr is a terminal, and their options).
  explicit TerminalLine(bool enabled) : enabled_(enabled), start_(Clock::now()), lastDraw_(start_) {}

  // Whether a redraw is due now (then the caller formats its text and calls draw()).
  bool due() {
    if (!enabled_) return false;
    const auto now = Clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - lastDraw_ < std::chrono::milliseconds(250))
      return false;
    lastDraw_ = now;
    return true;
  }
  double elapsedSeconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  void draw(const char* text) {
    // \r and "erase to end of line": the line is redrawn in place whatever its previous length.
    std::fprintf(stderr, "\r\033[K%s", text);
    std::fflush(stderr);
    shown_ = true;
  }
  void erase() {
    if (!shown_) return;
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
    shown_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_, shown_ = false;
  Clock::time_point start_, lastDraw_;
};

}  // namespace support
