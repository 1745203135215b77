// meldc's messages ("file:line:col: error: text", then the source line and a caret) read back
// into a list the editor can underline and jump to.
#pragma once

#include <QString>
#include <vector>

namespace ide {

struct Diagnostic {
  QString file;
  int line = 0, column = 0;  // 1-based; 0 = no position
  QString severity;          // "error", "warning", "note"
  QString message;
};

// Every "file:line:col: severity: message" line of the text (other lines are context).
std::vector<Diagnostic> parseDiagnostics(const QString& text);

}  // namespace ide
