// Pass: `data TEMPLATE "file" [args].` directives (§4.4): the graph of a SNAP text file (one
// `src dst [weight]` per line, `#` comment lines) becomes constant axioms, one statement per fact,
// appended to the program's rules. Node ids are the file's (§6.1: the program is then numbered
// like `priority @cluster @static`, ids 0..max all exist). The templates and the facts they make:
//   stanford-snap              edge(src, dst, W), W a pseudo-random weight in 1..500
//   stanford-sssp-snap         edge(src, dst, W), W the third column
//   stanford-snap-basic        edge(src, dst)
//   stanford-snap-undirected   edge(src, dst) and edge(dst, src)
//   stanford-snap-pagerank     output(src, dst, 1/outdeg(src)) and input(dst, src, 1/outdeg(src))
//   stanford-snap-search       edge(src, dst), value(n, n) for every node, and for a random
//                              `fraction` % of the nodes search(n, k, L): search k (0, 1, ...) for
//                              the list L of fraction % of all nodes, drawn at random
//                              (`data stanford-snap-search "file" ["searches" "fraction"]`)
// The established compiler draws the random numbers from SBCL's generator, which cannot be
// reproduced; here they come from a fixed splitmix64 stream (the same file gives the same facts).
#pragma once

#include "meldc/ast/program.hpp"
#include "meldc/diagnostics.hpp"
#include "meldc/source.hpp"

namespace meldc {

// Reads the data files (relative paths: next to the file with the directive). False on errors.
bool importData(ast::Program& program, SourceManager& sources, Diagnostics& diag);

// Whether the program has a `data` directive (its nodes are then numbered as in the file).
bool hasDataDirective(const ast::Program& program);

}  // namespace meldc
