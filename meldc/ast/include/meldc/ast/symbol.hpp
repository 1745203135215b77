// Names folded once. Meld names compare case-insensitively (§1.3): the front end interns every
// name of the AST (internNames, below) and the passes compare and look up Symbols, small integers,
// instead of folding strings at every use. The spelling stays in the AST for messages.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace meldc::ast {

struct Symbol {
  std::uint32_t id = UINT32_MAX;
  bool valid() const { return id != UINT32_MAX; }
  friend bool operator==(Symbol, Symbol) = default;
  friend auto operator<=>(Symbol, Symbol) = default;
};

class SymbolTable {
 public:
  Symbol intern(std::string_view name);      // folds case
  Symbol find(std::string_view name) const;  // invalid when the name was never interned
  const std::string& text(Symbol s) const { return names_.at(s.id); }  // folded
  std::size_t size() const { return names_.size(); }

 private:
  std::vector<std::string> names_;
  std::unordered_map<std::string, std::uint32_t> ids_;
};

struct Program;
// Gives every name of the program its Symbol (declarations, subgoals, calls, constants, named
// types, directives, ground facts) and interns the built-in predicates and functions, so that
// lookups by those names always find a symbol. Passes that add AST later intern what they add.
void internNames(Program& program);

}  // namespace meldc::ast

template <>
struct std::hash<meldc::ast::Symbol> {
  std::size_t operator()(meldc::ast::Symbol s) const noexcept { return s.id; }
};
