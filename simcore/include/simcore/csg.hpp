// VisibleSim's constructive solid geometry (`<csg content="..."/>` in a world's block list): an
// OpenSCAD-like text of shapes whose inside becomes blocks.
//
// The language (as VisibleSim reads it):
//   statement := NAME '=' expr ';'                              a variable
//              | 'module' NAME '(' [NAME {',' NAME}] ')' '{' statements '}'
//              | shape
//   shape     := ('union' | 'difference' | 'intersection') '(' ')' '{' statements '}'
//              | ('translate' | 'rotate' | 'scale' | 'color') '(' vector ')' shape
//              | 'cube' '(' vector [',' bool] ')' ';'           size, centred
//              | 'sphere' '(' expr ')' ';'                      radius
//              | 'cylinder' '(' expr ',' expr [',' expr [',' bool]] ')' ';'
//                                                               height, radius (bottom, top: a cone), centred
//              | 'torus' '(' expr ',' expr ')' ';'
//              | NAME '(' [expr {',' expr}] ')' ';'             a module call
//   vector    := '[' expr ',' expr ',' expr ']'
// Expressions: numbers, variables, + - * / ^ (power), unary minus, parentheses, the constants
// _pi and _e and the functions sin cos tan asin acos atan sinh cosh tanh sqrt abs exp ln log log2
// log10 sign rint (one argument) and min max (two or more). `rotate` takes degrees and turns
// about x, then y, then z; `color` takes 0..255 components and the outermost color wins. Only the
// first top-level shape is the solid; later ones are ignored (VisibleSim's rule), with a warning.
// Geometry follows VisibleSim exactly, quirks included (a torus measures its distance in 3D, the
// bounding box of a transform is that of its last child).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "simcore/lattice.hpp"

namespace simcore {

// A syntax or evaluation error at a byte offset of the content.
class CsgError : public std::runtime_error {
 public:
  CsgError(std::size_t offset, const std::string& message) : std::runtime_error(message), offset_(offset) {}
  std::size_t offset() const { return offset_; }

 private:
  std::size_t offset_;
};

struct CsgBox {
  Vec3 min, max;
};

struct CsgNode;

class CsgSolid {
 public:
  // Parses and evaluates the text; throws CsgError.
  static CsgSolid parse(std::string_view content);
  CsgSolid(CsgSolid&&) noexcept;
  CsgSolid& operator=(CsgSolid&&) noexcept;
  ~CsgSolid();

  // Whether the point is inside; `color` (0xRRGGBB) is set by the color() around the part hit.
  bool inside(const Vec3& p, std::optional<std::uint32_t>& color) const;
  CsgBox boundingBox() const;
  // Messages about what was ignored (shapes after the first).
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  CsgSolid() = default;
  std::unique_ptr<CsgNode> root_;
  std::vector<std::string> warnings_;
};

}  // namespace simcore
