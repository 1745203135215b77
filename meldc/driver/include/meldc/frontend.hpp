// The front-end pipeline of the driver: load (parse + include merging), apply -D definitions,
// resolve names, the semantic checks (bindings, homes, types), then node renumbering (§6.1: node
// literals hold internal ids afterwards, Program::nodeTable has the pairs). One function so that tests
// run exactly what `meldc --check` runs.
// Localization (localize.hpp, §6.7) then rewrites the rules whose bodies span several nodes.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"

namespace meldc {

struct FrontEndInput {
  std::string path;
  std::vector<std::string> includeDirs;
  std::vector<std::pair<std::string, std::string>> defines;  // NAME, VALUE (a Meld expression)
  // Robots (§7.3): node ids are block ids, so literals keep their source ids and every id up to
  // the largest literal exists, as with `priority @cluster @static`.
  bool identityNodes = false;
  // Facts of literals only take the compact path (ast/ground_fact.hpp); off, every fact is an
  // ast::Rule from the parser on.
  bool groundFacts = true;
};

// Returns the checked program, or nullopt when there were errors (all reported to `diag`).
std::optional<ast::Program> runFrontEnd(const FrontEndInput& input, SourceManager& sources,
                                        Diagnostics& diag);

}  // namespace meldc
