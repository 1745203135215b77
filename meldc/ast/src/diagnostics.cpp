#include "meldc/diagnostics.hpp"

namespace meldc {

namespace {

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Error:
      return "error";
    case Severity::Warning:
      return "warning";
    case Severity::Note:
      return "note";
  }
  return "error";
}

// Caret line: the characters before the column are replaced by blanks (tabs kept, so the caret
// lines up whatever the tab width); UTF-8 continuation bytes do not count as characters.
std::string caretLine(std::string_view source, uint32_t col) {
  std::string caret;
  uint32_t seen = 1;
  for (size_t i = 0; i < source.size() && seen < col; ++i) {
    unsigned char c = static_cast<unsigned char>(source[i]);
    if ((c & 0xC0) == 0x80) continue;
    caret += c == '\t' ? '\t' : ' ';
    ++seen;
  }
  while (seen < col) {  // a position just past the end of the line
    caret += ' ';
    ++seen;
  }
  caret += '^';
  return caret;
}

}  // namespace

void Diagnostics::errorNoLoc(const std::string& message) {
  ++errors_;
  out_ << "meldc: error: " << message << '\n';
}

void Diagnostics::report(Severity severity, SourceLoc loc, const std::string& message) {
  if (severity == Severity::Error) ++errors_;
  if (severity == Severity::Warning) ++warnings_;
  if (!loc.valid() || loc.file >= sources_.size()) {
    out_ << "meldc: " << severityName(severity) << ": " << message << '\n';
    return;
  }
  out_ << sources_.file(loc.file).path << ':' << loc.line << ':' << loc.col << ": " << severityName(severity)
       << ": " << message << '\n';
  std::string_view line = sources_.line(loc.file, loc.line);
  out_ << line << '\n' << caretLine(line, loc.col) << '\n';
}

}  // namespace meldc
