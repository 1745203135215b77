// Node renumbering (language reference §6.1): computes the initial node set of a checked program
// and the map source id -> internal id, then rewrites every node literal `@N` of the AST to its
// internal id. The (internal, source) pairs stay in Program::nodeTable for the bytecode writer.
//
//   1. per file, the distinct literals in order of first textual occurrence;
//   2. nodes(F) := literals(F), then for each include of F in reverse order of the include lines
//      nodes(F) := sbclUnion(nodes(F), nodes(I));
//   3. P := reverse(nodes(main file));
//   4. breadth-first numbering over the constant axioms of route predicates (default), or
//      `priority @cluster @static`: id = source id, and every id 0..max exists.
// `priority @cluster @random`: a permutation from a fixed random stream (cl-meld's is not
// reproducible); `data` directives: ids of the graph file, numbered like `@cluster @static`.
// Literals that come from -DNAME=VALUE definitions are added at the end of nodes(main file).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"

namespace meldc {

// Rewrites the node literals of `program` and fills program.nodeTable: breadth-first (§6.1), the
// identity for `priority @cluster @static`, `data` and `identity` (robots), a reproducible random
// permutation for `priority @cluster @random`.
void renumberNodes(ast::Program& program, bool identity = false);

// The pieces of the algorithm, exposed for the tests.

// SBCL's `union` for short lists: S = the shorter list (y when the lengths are equal), G = the
// other; the result starts as S and each element of G not in S is prepended, in G's order.
std::vector<int64_t> sbclUnion(const std::vector<int64_t>& x, const std::vector<int64_t>& y);

// The queue algorithm of §6.1 step 4: `order` is P (an ordered set), `edges` is E (neighbour lists
// already in their final order). Returns the source ids in internal-id order.
std::vector<int64_t> numberBreadthFirst(const std::vector<int64_t>& order,
                                        std::map<int64_t, std::vector<int64_t>> edges);

}  // namespace meldc
