#include "diagnostics.hpp"

#include <QRegularExpression>

namespace ide {

std::vector<Diagnostic> parseDiagnostics(const QString& text) {
  static const QRegularExpression line(R"(^(.+?):(\d+):(\d+): (error|warning|note): (.*)$)");
  std::vector<Diagnostic> out;
  for (const QString& l : text.split('\n')) {
    const QRegularExpressionMatch m = line.match(l);
    if (!m.hasMatch()) continue;
    out.push_back(Diagnostic{m.captured(1), m.captured(2).toInt(), m.captured(3).toInt(), m.captured(4),
                             m.captured(5)});
  }
  return out;
}

}  // namespace ide
