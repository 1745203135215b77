#include "meldc/compile_progress_line.hpp"

#include <cstdio>

namespace meldc {

void CompileProgressLine::update(std::size_t done, std::size_t total) {
  if (!line_.due()) return;
  char text[160];
  std::snprintf(text, sizeof text, "%s: compiling native code: %zu/%zu parts (%3.0f%%)   wall %.1f s",
                tool_.c_str(), done, total, total ? 100.0 * double(done) / double(total) : 100.0,
                line_.elapsedSeconds());
  line_.draw(text);
}

}  // namespace meldc
