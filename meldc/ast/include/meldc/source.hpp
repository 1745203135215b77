// Source files and positions. Every AST node and diagnostic carries a SourceLoc.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace meldc {

// A position in a source file: file index in the SourceManager, 1-based line and column.
// Columns count characters (code points), a tab counts as one.
struct SourceLoc {
  uint32_t file = 0;
  uint32_t line = 0;
  uint32_t col = 0;
  bool valid() const { return line != 0; }
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

struct SourceFile {
  std::string path;  // as given (command line) or resolved from an include
  std::string text;
  std::vector<size_t> lineStarts;  // byte offsets of each line
};

// Owns the text of every file read in one compilation.
class SourceManager {
 public:
  // Adds a file from memory and returns its index.
  uint32_t add(std::string path, std::string text);
  // Reads a file from disk; returns false (and adds nothing) if it cannot be read.
  bool load(const std::string& path, uint32_t& index);
  const SourceFile& file(uint32_t index) const { return files_.at(index); }
  size_t size() const { return files_.size(); }
  // The text of a line (without its newline); empty when out of range.
  std::string_view line(uint32_t file, uint32_t line) const;

 private:
  std::vector<SourceFile> files_;
};

}  // namespace meldc
