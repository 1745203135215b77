// The lists a loop fetches ahead, carried from visit to visit (vm/engine/src/list_pipeline.hpp):
// at every visit, the cell on the way for the fact k on is that fact's list cell at depth
// listPipelineDepth(k) (one level deeper every kListPipelineSpacing visits), whatever the lengths
// of the lists (empty ones included) and however near the list's end the loop is.
#define BOOST_TEST_MODULE vm_list_pipeline
#include <boost/test/unit_test.hpp>

#include "../../vm/engine/src/list_pipeline.hpp"
#include "vm_fixture.hpp"

using namespace vmtest;
using meldvm::ConsCell;
using meldvm::ListPipeline;

namespace {

const ConsCell* cellAt(const Database& db, PredId p, FactRef f, int depth) {
  if (f == kNoFact) return nullptr;
  auto* cell = static_cast<const ConsCell*>(db.args(p, f)[1].asObject());
  for (; depth > 0 && cell; --depth) cell = cell->tail;
  return cell;
}

FactRef ahead(const Database& db, PredId p, FactRef f, int k) {
  for (; k > 0 && f != kNoFact; --k) f = db.next(p, f);
  return f;
}

// Visits every fact of `placed` at node 0 as a loop does, checking the pipeline before each visit;
// returns the number of visits.
int visitAll(const Database& db, PredId placed) {
  const FactTable& table = db.table(placed);
  ListPipeline pipeline;
  int visits = 0;
  for (FactRef f = db.first(0, placed); f != kNoFact; f = db.next(placed, f), ++visits) {
    pipeline.step(table, f, 1);
    for (int k = 1; k <= ListPipeline::kAhead; ++k)
      BOOST_TEST(
          pipeline.cellAhead(k) == cellAt(db, placed, ahead(db, placed, f, k), ListPipeline::depthAhead(k)),
          "visit " << visits << ", fact " << k << " on");
  }
  return visits;
}

}  // namespace

BOOST_AUTO_TEST_CASE(each_visit_has_the_cell_at_its_depth_for_every_fact_ahead) {
  Store s;
  const TypeId ints = s.types.list(TypeTable::kInt);
  const PredId placed = s.linear("placed", {TypeTable::kInt, ints});
  Database& db = s.open(1);
  // Lists of every length from 0 to 14 and back, sharing tails as n-queens' placements do.
  std::vector<Value> lists{Value::nil()};
  for (int i = 1; i <= 14; ++i) lists.push_back(s.heap.cons(ints, I(i), lists.back()));
  for (int round = 0; round < 2; ++round)
    for (int i = 0; i < 15; ++i) {
      const int len = round == 0 ? i : 14 - i;
      db.addLinear(0, placed, std::vector<Value>{I(len), lists[std::size_t(len)]}.data());
    }
  BOOST_TEST(visitAll(db, placed) == 30);
  for (Value v : lists) s.heap.release(ints, v);
}

BOOST_AUTO_TEST_CASE(fewer_facts_than_the_pipeline_is_long) {
  Store s;
  const TypeId ints = s.types.list(TypeTable::kInt);
  const PredId placed = s.linear("placed", {TypeTable::kInt, ints});
  Database& db = s.open(1);
  const Value list = s.heap.makeList(ints, std::vector<Value>{I(1), I(2), I(3)});
  for (int i = 0; i < 3; ++i) db.addLinear(0, placed, std::vector<Value>{I(i), list}.data());
  BOOST_TEST(visitAll(db, placed) == 3);
  s.heap.release(ints, list);
}
