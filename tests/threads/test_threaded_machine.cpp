// The threaded VM (`meld -j N`, vm/threads): facts with boxed values crossing threads, created
// nodes on every thread, thread facts sent between threads, stop-program and run-time errors on
// one thread, and the serial dump for schedule-independent programs at several thread counts.
#define BOOST_TEST_MODULE threads_threaded_machine
#include <boost/test/unit_test.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "../meldc/compile_source.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/threaded_machine.hpp"

namespace {

std::string serialDump(const meldvm::Program& p) {
  meldvm::Machine m(p);
  m.run();
  return m.dump();
}

std::string threadedDump(const meldvm::Program& p, unsigned threads, std::string* output = nullptr) {
  std::ostringstream out;
  meldvm::MachineOptions o;
  o.output = &out;
  meldvm::ThreadedMachine m(p, o, threads);
  m.run();
  if (output) *output = out.str();
  return m.dump();
}

// `!edge(@i, @i+1)` round a ring of n nodes.
std::string ringEdges(int n) {
  std::string s;
  for (int i = 0; i < n; ++i)
    s += "!edge(@" + std::to_string(i) + ", @" + std::to_string((i + 1) % n) + ").\n";
  return s;
}

// A ring of 24 nodes (the literals are renumbered in order of appearance, so the ring visits
// every thread's range in turn) carrying a list, a string and a struct all the way round.
std::string ringProgram() {
  std::string s =
      "type route edge(node, node).\n"
      "type linear token(node, list int, string, :(int, float), int).\n"
      "type linear seen(node, list int, string, :(int, float)).\n"
      "token(@0, [], \"go\", :(0, 0.5), 23).\n";
  s += ringEdges(24);
  s += "token(A, L, S, P, N), !edge(A, B), N > 0 -o "
       "token(B, [N | L], concatenate(S, int2str(N)), P, N - 1), seen(A, L, S, P).\n"
       "token(A, L, S, P, 0) -o seen(A, L, S, P).\n";
  return s;
}

}  // namespace

BOOST_AUTO_TEST_CASE(boxed_values_cross_threads_and_the_dump_is_the_serial_one) {
  const auto p = compileSource(ringProgram());
  const std::string serial = serialDump(*p);
  BOOST_TEST(serial.find("seen([1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23], ") !=
             std::string::npos);
  for (unsigned threads : {2u, 3u, 4u, 7u})
    BOOST_TEST(threadedDump(*p, threads) == serial, "threads " << threads);
}

BOOST_AUTO_TEST_CASE(scalar_facts_cross_threads_bit_for_bit_and_so_do_retractions) {
  // Facts with only int, float and node fields travel as their bits (shard_mail.cpp): a token
  // round a ring of 24 nodes carrying a float that is not a short decimal, and the node it came
  // from. Retractions too: node 44's min aggregate (§6.8) first hears 140 over 14 costly roads,
  // then 22 over 22 cheap ones, and the fact it reported to node 0 (another thread's) from 140 is
  // taken back there by a negative fact.
  std::string s =
      "type route edge(node, node).\n"
      "type linear tok(node, int, float, node).\n"
      "type linear got(node, int, float, node).\n"
      "type route road(node, node, int).\n"
      "type dist(node, min int).\n"
      "type cand(node, int).\n"
      "type report(node, node).\n"
      "tok(@0, 23, 0.1, @0).\n"
      "!dist(@30, 0).\n";
  s += ringEdges(24);
  for (int i = 30; i < 44; ++i)
    s += "!road(@" + std::to_string(i) + ", @" + std::to_string(i + 1) + ", 10).\n";
  for (int i = 50; i < 70; ++i)
    s += "!road(@" + std::to_string(i) + ", @" + std::to_string(i + 1) + ", 1).\n";
  s += "!road(@30, @50, 1). !road(@70, @44, 1).\n"
       "tok(A, N, F, W), !edge(A, B), N > 0 -o tok(B, N - 1, F * 1.1 - 0.03, A), got(A, N, F, W).\n"
       "!report(@44, @0).\n"
       "!dist(A, D), !road(A, B, W) -o !dist(B, D + W).\n"
       "!dist(A, D), !report(A, R) -o !cand(R, D).\n";
  const auto p = compileSource(s);
  const std::string serial = serialDump(*p);
  BOOST_TEST(serial.find("!cand(22)") != std::string::npos, serial);
  BOOST_TEST(serial.find("!cand(140)") == std::string::npos, serial);
  for (unsigned threads : {2u, 3u, 4u})
    BOOST_TEST(threadedDump(*p, threads) == serial, "threads " << threads);
}

BOOST_AUTO_TEST_CASE(more_threads_than_nodes) {
  const auto p =
      compileSource("type linear a(node, int).\na(@0, 1). a(@1, 2).\na(A, N), N < 5 -o a(A, N + 2).\n");
  BOOST_TEST(threadedDump(*p, 6) == serialDump(*p));
}

BOOST_AUTO_TEST_CASE(nodes_created_on_every_thread_are_collected_like_the_serial_ones) {
  // Each of 8 nodes creates a chain of 3 nodes that reports back; the chain nodes keep nothing
  // but the last, so the GC (§6.10) must drop the rest on every thread.
  std::string s =
      "type linear grow(node, node, int).\ntype linear back(node, int).\ntype linear kept(node, int).\n"
      "type linear total(node, int).\n";
  for (int i = 0; i < 8; ++i)
    s += "grow(@" + std::to_string(i) + ", @" + std::to_string(i) + ", 3). total(@" + std::to_string(i) +
         ", 0).\n";
  s += "grow(A, R, N), N > 0 -o exists B. (grow(B, R, N - 1)).\n"
       "grow(A, R, 0) -o back(R, 1), kept(A, 1).\n"
       "back(A, X), total(A, T) -o total(A, T + X).\n";
  const auto p = compileSource(s);
  const std::string serial = serialDump(*p);
  auto shape = [](const std::string& dump) {
    std::multiset<std::string> lines;
    std::istringstream in(std::regex_replace(dump, std::regex("^[0-9]+\n", std::regex::multiline), "node\n"));
    for (std::string l; std::getline(in, l);) lines.insert(l);
    return lines;
  };
  for (unsigned threads : {2u, 4u}) {
    const std::string dump = threadedDump(*p, threads);
    BOOST_TEST((shape(dump) == shape(serial)), "threads " << threads << ":\n" << dump);
    BOOST_TEST(std::count(dump.begin(), dump.end(), '\n') == std::count(serial.begin(), serial.end(), '\n'));
  }
}

BOOST_AUTO_TEST_CASE(thread_facts_are_sent_to_other_threads) {
  // Every thread node greets every other thread once: each ends with threads - 1 greetings.
  const auto p = compileSource(
      "type linear hello(thread, int).\ntype linear start(thread).\n"
      "start(T).\n"
      "start(T) -o {T2, I | !other-thread(T, T2, I) | hello(T2, 1)}.\n");
  for (unsigned threads : {2u, 3u}) {
    const std::string dump = threadedDump(*p, threads);
    std::size_t count = 0;
    for (std::size_t at = dump.find("hello(1)"); at != std::string::npos; at = dump.find("hello(1)", at + 1))
      ++count;
    BOOST_TEST(count == threads * (threads - 1), dump);
  }
}

BOOST_AUTO_TEST_CASE(write_string_lines_of_all_threads_come_whole) {
  std::string s = "type linear say(node, int).\n";
  for (int i = 0; i < 40; ++i) s += "say(@" + std::to_string(i) + ", " + std::to_string(i) + ").\n";
  s += "say(A, N) -o write-string(A, concatenate(\"line \", int2str(N))).\n";
  const auto p = compileSource(s);
  std::string output;
  threadedDump(*p, 4, &output);
  std::set<std::string> lines;
  std::istringstream in(output);
  for (std::string l; std::getline(in, l);) lines.insert(l);
  BOOST_TEST(lines.size() == 40u);
  for (int i = 0; i < 40; ++i) BOOST_TEST(lines.count("line " + std::to_string(i)) == 1u);
}

BOOST_AUTO_TEST_CASE(stop_program_on_one_thread_stops_them_all) {
  // The node that stops the program runs first on thread 0 (§6.1 numbers the node literals last
  // seen first: @5 is node 0); the nodes of the other threads would count forever, each in one
  // endless node run.
  std::string s = "type linear tick(node, int).\ntype linear halt(node).\n";
  for (int i = 0; i < 5; ++i) s += "tick(@" + std::to_string(i) + ", 0).\n";
  s += "halt(@5).\n";
  s += "halt(A) -o stop-program(A).\ntick(A, N) -o tick(A, N + 1).\n";
  const auto p = compileSource(s);
  meldvm::ThreadedMachine m(*p, {}, 3);
  m.run();
  BOOST_TEST(m.stopped());
}

BOOST_AUTO_TEST_CASE(a_run_time_error_on_one_thread_ends_the_run_with_its_message) {
  std::string s = "type linear d(node, int).\n";
  // Node 3 (@5, numbered as above), the first node of thread 1, divides by zero; the others would
  // loop forever.
  for (int i = 0; i < 9; ++i) s += "d(@" + std::to_string(i) + ", " + std::to_string(i == 5 ? 0 : 1) + ").\n";
  s += "d(A, N) -o d(A, 10 / N).\n";
  const auto p = compileSource(s);
  meldvm::ThreadedMachine m(*p, {}, 3);
  try {
    m.run();
    BOOST_FAIL("no error");
  } catch (const meldvm::RuntimeError& e) {
    BOOST_TEST(std::string(e.what()).find("node @3") != std::string::npos, e.what());
  }
}

BOOST_AUTO_TEST_CASE(memory_use_counts_the_run_buffers_and_the_batches_between_threads) {
  // The token crosses between threads: the rule runs' buffers and each thread's batches are
  // memory the VM holds (kept at the size of the largest run), part of the total.
  // (Against one thread of the threaded VM: the serial VM also keeps room for native code's sends.)
  const auto p = compileSource(ringProgram());
  meldvm::ThreadedMachine single(*p, {}, 1);
  single.run();
  const meldvm::MemoryUse one = single.memoryUse();
  BOOST_TEST(one.buffers > 0u);
  meldvm::ThreadedMachine m(*p, {}, 3);
  m.run();
  const meldvm::MemoryUse three = m.memoryUse();
  BOOST_TEST(three.buffers > 3 * one.buffers);  // each thread's own, and the batches on top
  BOOST_TEST(three.total() == three.factTables + three.listHeads + three.heaps + three.mailboxes +
                                  three.scheduling + three.buffers);
}

BOOST_AUTO_TEST_CASE(per_thread_statistics_add_up) {
  const auto p = compileSource(ringProgram());
  meldvm::ThreadedMachine m(*p, {}, 3);
  m.run();
  const std::vector<meldvm::ThreadStats> threads = m.threadStats();
  BOOST_REQUIRE(threads.size() == 3u);
  std::uint64_t derived = 0, out = 0, in = 0;
  for (const auto& t : threads) derived += t.factsDerived, out += t.factsOut, in += t.factsIn;
  BOOST_TEST(derived == m.stats().factsDerived);
  BOOST_TEST(out == in);
  BOOST_TEST(out >= 3u);  // the token crosses from each thread's range to the next at least once
}

// 64 nodes; the 32 of thread 0's range (the literals seen last get the low ids, §6.1) count
// down from 100000 in their first run, the others have nothing to do.
std::string countdownProgram() {
  std::string s = "type linear w(node, int).\ntype route edge(node, node).\ntype linear got(node, int).\n";
  for (int i = 0; i < 64; ++i) {
    s += "w(@" + std::to_string(i) + ", " + (i >= 32 ? "100000" : "1") + ").\n";
    s += "!edge(@" + std::to_string(i) + ", @" + std::to_string((i + 1) % 64) + ").\n";
  }
  return s +
         "w(A, N), N > 0 -o w(A, N - 1).\n"
         "w(A, 0), !edge(A, B) -o got(B, 1).\n";
}

BOOST_AUTO_TEST_CASE(an_idle_thread_steals_queued_nodes_even_from_a_long_node_run) {
  // One thread's nodes count down, 100000 rules per node run; the other runs out of work at once
  // and takes nodes waiting in the first one's queue, facts, messages and all. It asks while the
  // first is in the middle of a run: that thread joins the rebalance between two rules (it does
  // not wait for the run's end), gives waiting nodes but never the running one, and the run goes
  // on where it was. The dump is the serial one.
  const auto p = compileSource(countdownProgram());
  const std::string serial = serialDump(*p);
  meldvm::ThreadedMachine m(*p, {}, 2);
  m.run();
  BOOST_TEST(m.dump() == serial);
  std::uint64_t taken = 0, given = 0, rebalances = 0, midRun = 0;
  for (const auto& t : m.threadStats())
    taken += t.nodesTaken, given += t.nodesGiven, rebalances += t.rebalances, midRun += t.midRunRebalances;
  BOOST_TEST(taken > 0u);
  BOOST_TEST(taken == given);
  BOOST_TEST(midRun > 0u);
  BOOST_TEST(midRun < rebalances);  // the thread that asked was between runs
}

BOOST_AUTO_TEST_CASE(set_cpu_moves_nodes_to_another_thread_where_they_get_just_moved) {
  // Every node asks to go to the leader thread #T0: the nodes of the other threads move there
  // (facts and all), are pinned, and only then get just-moved (§5.7), so every node ends with
  // cpu-id #T0 and thread 0 counts all 8 as static in the end.
  const auto p = compileSource(
      "type linear go(node).\ntype linear where(node, thread, int).\n"
      "go(@0). go(@1). go(@2). go(@3). go(@4). go(@5). go(@6). go(@7).\n"
      "go(A), !leader-thread(T, L) -o set-cpu(A, L).\n"
      "just-moved(A) -o where(A, cpu-id(A), cpu-static(A)).\n");
  for (unsigned threads : {2u, 3u}) {
    meldvm::ThreadedMachine m(*p, {}, threads);
    m.run();
    const std::string dump = m.dump();
    std::size_t onLeader = 0;
    for (std::size_t at = dump.find("where(#T0, "); at != std::string::npos;
         at = dump.find("where(#T0, ", at + 1))
      ++onLeader;
    BOOST_TEST(onLeader == 8u, dump);
    BOOST_TEST(dump.find("where(#T1") == std::string::npos, dump);
    // Thread 0 took at least every node that did not start on it (more if some were stolen
    // from it first).
    BOOST_TEST(m.threadStats()[0].nodesTaken >= 8u - 8u / threads, "threads " << threads);
  }
}

// Node @0 conses 40 heads onto one 600-element list and sends each to another node, 20 of them
// in the other thread's range: the lists are handed over (heap.hpp, Heap::share), so the
// receiving thread holds the sender's cells, not 20 copies of 600 cells.
BOOST_AUTO_TEST_CASE(lists_consed_on_one_tail_cross_threads_still_sharing_it) {
  std::string s =
      "type route edge(node, node, int).\n"
      "type linear base(node, list int).\n"
      "type linear got(node, list int).\n"
      "type linear fan(node).\n"
      "fan(@0).\n"
      "base(@0, [";
  for (int i = 0; i < 600; ++i) {
    if (i) s += ',';
    s += std::to_string(i);
  }
  s += "]).\n";
  for (int k = 1; k <= 40; ++k)
    s += "!edge(@0, @" + std::to_string(40 + k) + ", " + std::to_string(k) + ").\n";
  s += "fan(A), base(A, L) -o {B, K | !edge(A, B, K) | got(B, [K | L])}.\n";
  const auto p = compileSource(s);
  const std::string serial = serialDump(*p);
  BOOST_TEST(serial.find("got([40,0,1,2,") != std::string::npos);
  meldvm::MachineOptions o;
  std::ostringstream out;
  o.output = &out;
  meldvm::ThreadedMachine m(*p, o, 2);
  m.run();
  BOOST_TEST(m.dump() == serial);
  // Copies would take 20 x 601 cells of 24 bytes (288 KB) in the receiving heap; handed over,
  // the sender's 640 cells are all there is, as in the serial heap.
  meldvm::Machine serialMachine(*p);
  serialMachine.run();
  BOOST_TEST(m.memoryUse().heaps <= 2 * serialMachine.memoryUse().heaps);
}
