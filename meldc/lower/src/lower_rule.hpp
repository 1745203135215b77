// Lowering of one rule body and head into a code block (§6.4.3): the match plan (nested loops,
// tests, constraints as soon as their variables are bound) and the head (derivations, sends,
// updates, coordination, comprehensions, aggregate constructs, exists, conditionals).
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "code_builder.hpp"
#include "lower_context.hpp"
#include "lower_expr.hpp"
#include "rule_analysis.hpp"

namespace meldc {

class RuleLowering {
 public:
  using Label = CodeBuilder::Label;
  enum class Mode { Rule, Comprehension };

  RuleLowering(Lowering& L, CodeBuilder& cb, std::string hostVar)
      : L_(L), cb_(cb), ex(L, cb), hostVar_(std::move(hostVar)) {}

  // Body arguments that are these variables are matched as `_` (singletonVariables).
  void ignoreVariables(std::set<std::string> names) { ignored_ = std::move(names); }
  // HOST r and binds the host variable to it (nothing for a rule without one: thread facts only).
  void bindHost();

  // The loops of `plan` from slot `firstSlot` on; `outerFail` is where a test that fails before
  // the first loop goes. `prebound`: slot firstSlot is bound by the engine (persistent process).
  // At the innermost point runs `onMatch` and ends with FIRE (Rule) or CFIRE (Comprehension).
  void match(const BodyPlan& plan, std::uint32_t firstSlot, Label outerFail, Mode mode, bool prebound,
             const std::function<void()>& onMatch);

  // Head items; `plan` (may be null) says which items are dropped or become the UPDATE.
  // `nextSlot`: first free slot for comprehensions and aggregates.
  void head(const std::vector<ast::Term>& items, const BodyPlan* plan, std::uint32_t nextSlot,
            std::uint32_t firstSlot = 0);
  // One derived fact (or action, or instruction). `localNode`: a literal home equal to it is the
  // host (axiom blocks of that node).
  void subgoal(const ast::Term& t, std::optional<std::int64_t> localNode = std::nullopt);
  // `X = e` binding X when unbound; false if the term is not such an assignment.
  bool assignment(const ast::Term& t);

 private:
  struct Pending {
    const ast::Term* term = nullptr;  // a constraint, assignment or boolean call
    Reg reg = 0;                      // or: reg must equal expr (a deferred pattern test)
    const ast::Expr* expr = nullptr;
    bool isAssignment = false;
    bool done = false;
  };
  void flush(Label fail);
  // The home of a thread fact (§6.12): binds an unbound variable to THREAD, else tests it.
  void threadHome(const ast::Expr& home, Label fail);
  void pattern(std::uint32_t slot, std::uint32_t field, meldvm::TypeId type, const ast::Expr& arg,
               Label fail);
  void destructure(Reg r, const ast::Expr& pat, Label fail);
  // The field of an `index` directive whose argument is already bound here (ITER_KEY), if any.
  std::optional<std::uint32_t> indexedKey(const SubgoalPlan& s);
  void comprehension(const ast::Term& t, std::uint32_t slot);
  void aggregate(const ast::Term& t, std::uint32_t slot);
  void instruction(const ast::Term& t, Instruction which);

  Lowering& L_;
  CodeBuilder& cb_;

 public:
  ExprLowerer ex;

 private:
  std::string hostVar_;
  Reg host_ = 0;
  std::vector<Pending> pending_;
  std::set<std::string> ignored_;
  std::optional<std::uint32_t> keyField;  // the loop being lowered matches this field by its index
};

}  // namespace meldc
