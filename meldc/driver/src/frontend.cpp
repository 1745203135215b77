#include "meldc/frontend.hpp"

#include "meldc/bindings.hpp"
#include "meldc/case_folding.hpp"
#include "meldc/data_import.hpp"
#include "meldc/ground_facts.hpp"
#include "meldc/homes.hpp"
#include "meldc/includes.hpp"
#include "meldc/localize.hpp"
#include "meldc/names.hpp"
#include "meldc/parser.hpp"
#include "meldc/renumber.hpp"
#include "meldc/types.hpp"

namespace meldc {

namespace {

// -DNAME=VALUE: VALUE is parsed as an expression (diagnostics name the source "-DNAME").
void applyDefines(const FrontEndInput& input, ast::Program& program, SourceManager& sources,
                  Diagnostics& diag) {
  for (const auto& [name, value] : input.defines) {
    uint32_t file = sources.add("-D" + name, value);
    std::optional<ast::Expr> expr = parseExpression(file, sources, diag);
    if (!expr) continue;
    bool replaced = false;
    for (ast::ConstDecl& c : program.consts) {
      if (sameName(c.name, name)) {
        c.value = *expr;
        c.fromCommandLine = true;
        replaced = true;
      }
    }
    if (!replaced) {
      ast::ConstDecl c;
      c.loc = SourceLoc{file, 1, 1};
      c.name = name;
      c.value = std::move(*expr);
      c.fromCommandLine = true;
      program.consts.push_back(std::move(c));
    }
  }
}

}  // namespace

std::optional<ast::Program> runFrontEnd(const FrontEndInput& input, SourceManager& sources,
                                        Diagnostics& diag) {
  std::optional<ast::Program> program =
      loadProgram(input.path, input.includeDirs, sources, diag, input.groundFacts);
  if (!program) return std::nullopt;
  const ast::Program& p = *program;
  if (p.includes.empty() && p.predicates.empty() && p.rules.empty() && p.groundFacts.empty() &&
      p.consts.empty() && p.funs.empty() && p.directives.empty() && p.externs.empty() &&
      p.nodeTypes.empty() && p.typeAliases.empty() && p.exports.empty() && !diag.hasErrors()) {
    diag.error(SourceLoc{p.mainFile, 1, 1}, "the program is empty: no declaration, rule or fact");
    return std::nullopt;
  }
  applyDefines(input, *program, sources, diag);
  if (diag.hasErrors()) return std::nullopt;  // names would only repeat what is already broken
  if (!importData(*program, sources, diag)) return std::nullopt;
  ast::internNames(*program);           // names are folded once, here
  admitGroundFacts(*program, sources);  // the checks below see the facts they have to check
  resolveNames(*program, diag);
  if (diag.hasErrors()) return std::nullopt;  // the checks below assume resolved names
  checkBindings(*program, diag);
  checkHomes(*program, diag);
  checkTypes(*program, diag);
  if (diag.hasErrors()) return std::nullopt;
  renumberNodes(*program, input.identityNodes);
  localizeRules(*program, diag);  // rewrites bodies spanning nodes (§6.7)
  if (diag.hasErrors()) return std::nullopt;
  return program;
}

}  // namespace meldc
