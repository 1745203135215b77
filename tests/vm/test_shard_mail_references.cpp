// A boxed value that crosses shards (meldvm/shard_mail.hpp) keeps exactly one reference per holder:
// a sent fact's record takes over the sender's reference and the receiver's mailbox takes over the
// record's, a moving node's stored linear facts go to the taker's store the same way, and when the
// last holder lets go the cells go back to the heap that allocated them. (A count one too high
// would keep the cells forever; one too low would free them under a fact.)
#define BOOST_TEST_MODULE vm_shard_mail_references
#include <boost/test/unit_test.hpp>

#include "meldvm/shard_mail.hpp"
#include "shard_fixture.hpp"

using namespace bctest;

namespace {

// Nodes 0 and 1; `p(node, list int)` is stored, read by no rule.
struct ListProgram {
  TypeId listInt = 0;
  PredId p = 0;
  std::unique_ptr<Program> program = initOnlyProgram(2, [this](Program& g) {
    listInt = g.types.list(TypeTable::kInt);
    p = pred(g, "p", {listInt}, true);
  });
};

// Two shards: node 0 is thread 0's, node 1 thread 1's, unless a test moves it.
struct Shards {
  ListProgram lp;
  TestShardLink link;
  ShardMail mail{*lp.program};
  MailSlabs mailSlabs{2};
  std::unique_ptr<Machine> shard[2];
  Shards() {
    link.owners = {0, 1};
    for (ThreadId t = 0; t < 2; ++t) {
      MachineOptions o;
      o.shard = &link;
      o.placement = {t, 2, t, t + 1};
      o.mailSlabs = &mailSlabs;
      shard[t] = std::make_unique<Machine>(*lp.program, std::move(o));
      while (shard[t]->runNext()) {
      }
    }
  }
  std::uint32_t count(Value v) const { return v.asObject()->refs & ~Object::kShared; }
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_sent_list_has_one_reference_at_the_receiver_and_goes_home_when_dropped) {
  Shards s;
  Heap& home = s.shard[0]->heap();
  const std::vector<Value> items = {Value::fromInt(1), Value::fromInt(2), Value::fromInt(3)};
  const Value list = home.makeList(s.lp.listInt, items);  // thread 0 holds its one reference
  const std::size_t before = home.liveObjects();
  MailBytes bytes;
  s.mail.putFact(bytes, home, 1, s.lp.p, &list, false);  // the record takes it over
  BOOST_TEST(s.count(list) == 1u);
  ShardMail::Taken taken;
  s.mail.apply(*s.shard[1], bytes, taken);  // thread 1's mailbox takes it over
  BOOST_TEST(taken.facts == 1u);
  BOOST_TEST(s.count(list) == 1u);
  while (s.shard[1]->runNext()) {
  }
  BOOST_TEST(s.shard[1]->database().factCount(1, s.lp.p) == 1u);
  BOOST_TEST(s.count(list) == 1u);  // the stored fact's
  BOOST_TEST(home.liveObjects() == before);

  // A second list waits in node 1's mailbox, unread.
  const Value waiting = home.makeList(s.lp.listInt, std::vector<Value>{Value::fromInt(9)});
  MailBytes more;
  s.mail.putFact(more, home, 1, s.lp.p, &waiting, false);
  s.mail.apply(*s.shard[1], more, taken);
  BOOST_TEST(s.count(waiting) == 1u);

  // Node 1 moves to thread 0 with its fact and its message: still one reference each, now the
  // taker's store's and mailbox's.
  MailBytes move;
  s.mail.putNode(move, *s.shard[1], 1, false);
  s.link.owners[1] = 0;
  s.mail.apply(*s.shard[0], move, taken);
  BOOST_TEST(taken.nodes == 1u);
  BOOST_TEST(s.shard[0]->database().factCount(1, s.lp.p) == 1u);
  BOOST_TEST(s.count(list) == 1u);
  BOOST_TEST(s.count(waiting) == 1u);
  while (s.shard[0]->runNext()) {
  }
  BOOST_TEST(s.shard[0]->database().factCount(1, s.lp.p) == 2u);
  BOOST_TEST(s.count(waiting) == 1u);

  s.shard[1]->releaseAll();  // thread 1 holds nothing of them any more
  BOOST_TEST(home.liveObjects() == before + 1);
  s.shard[0]->releaseAll();  // the last holder: the four cells go
  BOOST_TEST(home.liveObjects() == before - 3);
}

BOOST_AUTO_TEST_CASE(a_moving_nodes_waiting_messages_go_as_they_are_with_their_values_shared) {
  Shards s;
  Heap& home = s.shard[1]->heap();
  // A list of thread 1's own waits in node 1's mailbox: private, one reference (the mailbox's).
  const Value mine = home.makeList(s.lp.listInt, std::vector<Value>{Value::fromInt(5), Value::fromInt(6)});
  s.shard[1]->receive(1, s.lp.p, &mine, false, /*adopt=*/true);
  BOOST_TEST((mine.asObject()->refs & Object::kShared) == 0);
  BOOST_TEST(s.count(mine) == 1u);
  MailBytes move;
  s.mail.putNode(move, *s.shard[1], 1, false);
  BOOST_TEST((mine.asObject()->refs & Object::kShared) != 0);  // with every cell it reaches
  BOOST_TEST((listTail(mine).asObject()->refs & Object::kShared) != 0);
  BOOST_TEST(!s.shard[1]->hasWork(1));
  s.link.owners[1] = 0;
  ShardMail::Taken taken;
  s.mail.apply(*s.shard[0], move, taken);
  BOOST_TEST(s.shard[0]->hasWork(1));
  BOOST_TEST(s.count(mine) == 1u);  // the taker's mailbox's, as before the move
  while (s.shard[0]->runNext()) {
  }
  BOOST_TEST(s.shard[0]->database().factCount(1, s.lp.p) == 1u);  // the message, stored
  s.shard[0]->releaseAll();
  s.shard[1]->releaseAll();
}

BOOST_AUTO_TEST_CASE(a_fact_for_a_node_the_receiver_does_not_hold_leaves_the_reference_to_be_released) {
  Shards s;
  Heap& home = s.shard[0]->heap();
  const Value list = home.makeList(s.lp.listInt, std::vector<Value>{Value::fromInt(7)});
  const std::size_t before = home.liveObjects();
  MailBytes bytes;
  s.mail.putFact(bytes, home, 5, s.lp.p, &list, false);  // node 5 does not exist
  ShardMail::Taken taken;
  BOOST_CHECK_THROW(s.mail.apply(*s.shard[1], bytes, taken), RuntimeError);
  BOOST_TEST(home.liveObjects() == before - 1);  // the record's reference was released: freed
}
