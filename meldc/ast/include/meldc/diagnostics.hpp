// Diagnostics in the house format:  file:line:col: error: message
// followed by the source line and a caret under the column.
#pragma once

#include <ostream>
#include <string>

#include "meldc/source.hpp"

namespace meldc {

enum class Severity { Error, Warning, Note };

class Diagnostics {
 public:
  Diagnostics(const SourceManager& sources, std::ostream& out) : sources_(sources), out_(out) {}

  void error(SourceLoc loc, const std::string& message) { report(Severity::Error, loc, message); }
  void warning(SourceLoc loc, const std::string& message) { report(Severity::Warning, loc, message); }
  void note(SourceLoc loc, const std::string& message) { report(Severity::Note, loc, message); }
  // A diagnostic without a position (e.g. a file given on the command line that cannot be read).
  void errorNoLoc(const std::string& message);

  void report(Severity severity, SourceLoc loc, const std::string& message);

  // Passes on what `other` reported into `text` (its stream's contents): a caller that may
  // discard a tentative pass collects its diagnostics apart, then keeps them.
  void append(const Diagnostics& other, const std::string& text) {
    out_ << text;
    errors_ += other.errors_;
    warnings_ += other.warnings_;
  }

  int errorCount() const { return errors_; }
  int warningCount() const { return warnings_; }
  bool hasErrors() const { return errors_ > 0; }

 private:
  const SourceManager& sources_;
  std::ostream& out_;
  int errors_ = 0;
  int warnings_ = 0;
};

}  // namespace meldc
