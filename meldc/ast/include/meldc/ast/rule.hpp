// Statements (§5.1): rules `body -o head.`, `head :- body.`, selector rules, and facts (axioms).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "meldc/ast/term.hpp"
#include "meldc/source.hpp"

namespace meldc::ast {

enum class RuleKind {
  Fact,     // head.
  Linear,   // body -o head.
  Datalog,  // head :- body.   (and `:- body.`)
};

enum class SelectorKind { Min, Random };

struct Selector {  // [:min W | body] -o head.
  SourceLoc loc;
  SelectorKind kind = SelectorKind::Min;
  std::string var;
};

struct Rule {
  SourceLoc loc;
  RuleKind kind = RuleKind::Fact;
  std::optional<Selector> selector;
  std::vector<Term> body;
  std::vector<Term> head;  // empty for `-o 1.`, `-o .` and `:- body.`
  bool generated = false;  // made by localization (§6.7); loc is that of the rule it comes from
};

}  // namespace meldc::ast
