// Pass: localization (§6.7). A rule body may use facts stored at a neighbour Y of the host X (the
// home of the first body subgoal) reached through a route subgoal `r(X, Y, ...)` at the host (Y is
// the route's second argument). The VM only matches facts of one node, so the rule is rewritten,
// as cl-meld does (the generated predicates show in database dumps, so their names matter):
//
//  * the inverse route `___` + the route name reversed (declared spelling, `neighbor` ->
//    `___robhgien`; flags route + reverse route; fields 0 and 1 swapped) and, once per route, the
//    rule `r(X0, X1, R...) -o ___inv(X1, X0, R...)` (with `!` marks for a persistent route);
//  * a rule whose host part is only the route subgoal moves to the neighbour: the route subgoal
//    becomes `___inv(Y, X, ...)` in place;
//  * otherwise, per route edge with facts at its neighbour, a helper `__mangledname<k>(node, V...)`
//    (k from 1 per compilation, in rule order; linear if a neighbour subgoal is linear), the rule
//    `___inv(Y, X, ...), <items at Y> -o __mangledname<k>(X, V...)`, and the original becomes
//    `__mangledname<k>(X, V...), <rest of the body> -o head`.
//
// V = the variables bound at the neighbour (by its subgoals, the route's arguments, or assignments
// placed there) that the rest of the rule uses, except X. cl-meld's order is implementation-defined
// (§6.7); ours: the int variables first, then the others, each group in order of first occurrence
// in the rule (body, then head). A constraint or assignment goes to the neighbour when it only uses
// variables bound there and at least one not bound at the host; otherwise it stays at the host.
//
// Generated rules are ordinary rules (flag `generated`, loc of the user rule they come from; an
// inverse route declaration keeps the loc of the route declaration), placed before all statements
// in creation order (inverse rule on first use of its route, then the helper rule); generated
// predicates are appended to the table: helpers in creation order, then inverse routes.
//
// Nodes further away (X -> Y -> Z through route subgoals, §6.7 "reachable from the host") go with
// the edge of the host's neighbour they are reached through: the rule moved to Y, or the helper
// rule at Y, still spans nodes and is localized again from Y, as cl-meld does edge by edge. Its
// helpers are numbered depth first (the edge's helper, then those of the nodes beyond it); the
// deeper generated rules come before the one at Y. Programs without multi-node bodies are left
// exactly as they are.
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

// Runs on a program that passed the checks (names, bindings, homes, types).
void localizeRules(ast::Program& program, Diagnostics& diag);

}  // namespace meldc
