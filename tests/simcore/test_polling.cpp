#define BOOST_TEST_MODULE simcore_polling
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <csignal>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "simcore/blockcode_polling.h"
#include "test_support.hpp"

// Polling block programs (blockcode_polling.h): each block's loop is a coroutine resumed by the
// events it waits for. Built twice: on the x86-64 switch and on POSIX ucontext (the fallback).

using namespace simcore;

namespace {

// The block traces of a run.
struct TraceLines final : SimulationObserver {
  explicit TraceLines(Simulation& sim) { sim.addObserver(this); }
  bool wantsEvents() const override { return false; }
  bool wantsMessages() const override { return false; }
  void onBlockTrace(const Simulation&, std::uint32_t, std::string_view text) override { lines.emplace_back(text); }
  std::vector<std::string> lines;
};

// What the blocks' loops saw, in order: one line per step, prefixed by the block and the time.
std::vector<std::string> gLog;

void note(vs_ctx* c, const std::string& what) {
  std::ostringstream line;  // (string concatenation here trips a false -Wrestrict of GCC 12)
  line << '#' << c->block << ' ' << vs_now(c) / VS_MS << "ms " << what;
  gLog.push_back(line.str());
}

// Blinky Blocks at `cells` running `program` (through `table`), not started yet.
std::unique_ptr<Simulation> prepare(const vs_polling_program& program, GridSize size, const std::vector<Cell>& cells,
                                    vs_blockcode& table) {
  gLog.clear();
  auto sim = testsupport::makeBlinky(size, cells);
  vs_polling_blockcode(&program, &table);
  sim->setBlockCode(&table);
  return sim;
}

std::unique_ptr<Simulation> run(const vs_polling_program& program, GridSize size, const std::vector<Cell>& cells,
                                vs_blockcode& table) {
  auto sim = prepare(program, size, cells, table);
  sim->runUntilEmpty();
  return sim;
}

// Block 0 sleeps 10 ms, sends "hi" to block 1, sleeps again and sends "bye". Block 1 waits for a
// message with a 15 ms timeout (none yet: timeout), then for messages for ever; a tap at 5 ms
// arrives while it waits for messages and is kept for its later wait for taps.
void talker(vs_ctx* c) {
  if (c->block == 0) {
    vs_sleep(c, 10 * VS_MS);
    note(c, "send hi");
    vs_send(c, targets::kBBRight, "hi", 2, 0);
    vs_sleep(c, 10 * VS_MS);
    note(c, "send bye");
    vs_send(c, targets::kBBRight, "bye", 3, 0);
    return;
  }
  vs_event ev;
  int rc = vs_wait_message(c, 5 * VS_MS, &ev);
  note(c, rc == VS_WAIT_TIMEOUT ? "timeout" : "message?");
  for (int i = 0; i < 2; ++i) {
    rc = vs_wait_message(c, 15 * VS_MS, &ev);
    note(c, rc == VS_OK ? "got " + std::string(static_cast<const char*>(ev.data), ev.size) : "timeout");
  }
  rc = vs_wait(c, VS_WAIT_KIND(VS_EV_TAP), 0, &ev);  // kept in the inbox since 7 ms
  note(c, rc == VS_OK ? "tap kept" : "no tap");
  rc = vs_wait(c, VS_WAIT_KIND(VS_EV_TAP), 0, &ev);
  note(c, rc == VS_OK ? "tap twice?" : "inbox empty");
}

}  // namespace

BOOST_AUTO_TEST_CASE(waits_sleeps_timeouts_and_the_inbox) {
  const vs_polling_program program{"talker", talker, 0, 0, 0, 0, nullptr};
  vs_blockcode table;
  auto sim = prepare(program, {2, 1, 1}, {{0, 0, 0}, {1, 0, 0}}, table);
  sim->scheduleTap(1, 7 * kMillisecond);
  sim->runUntilEmpty();
  // 38.4 kbit/s: "hi" takes 0.42 ms on the link, so it arrives at 10 ms (rounded down here).
  const std::vector<std::string> expected = {"#1 5ms timeout", "#0 10ms send hi", "#1 10ms got hi",
                                             "#0 20ms send bye", "#1 20ms got bye", "#1 20ms tap kept",
                                             "#1 20ms inbox empty"};
  BOOST_CHECK_EQUAL_COLLECTIONS(gLog.begin(), gLog.end(), expected.begin(), expected.end());
  // The cancelled timeouts never fired: 2 sleeps and 1 timeout are all the timers that ran.
  BOOST_CHECK_EQUAL(sim->statistics().eventsByKind[std::size_t(EventKind::Timer)], 3u);
}

namespace {

// Waits for taps only, for ever; every message meanwhile goes to the inbox (2 events fit).
void deaf(vs_ctx* c) {
  vs_event ev;
  vs_wait(c, VS_WAIT_KIND(VS_EV_TAP), VS_FOREVER, &ev);
  note(c, "tap; dropped " + std::to_string(vs_inbox_dropped(c)));
  while (vs_wait_message(c, 0, &ev) == VS_OK) note(c, "kept " + std::to_string(ev.size) + " bytes");
}

void chatter(vs_ctx* c) {
  if (c->block != 0) return deaf(c);
  for (int i = 1; i <= 4; ++i) vs_send(c, targets::kBBRight, "xxxx", uint32_t(i), 0);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_full_inbox_drops_and_says_so) {
  // Inbox of 2 events and 4 bytes: messages of 1 and 2 bytes fit (3 bytes), 3 and 4 do not.
  const vs_polling_program program{"chatter", chatter, 0, 0, 2, 4, nullptr};
  vs_blockcode table;
  auto sim = prepare(program, {2, 1, 1}, {{0, 0, 0}, {1, 0, 0}}, table);
  TraceLines traces(*sim);
  sim->scheduleTap(1, kSecond);
  sim->runUntilEmpty();
  const std::vector<std::string> expected = {"#1 1000ms tap; dropped 2", "#1 1000ms kept 1 bytes",
                                             "#1 1000ms kept 2 bytes"};
  BOOST_CHECK_EQUAL_COLLECTIONS(gLog.begin(), gLog.end(), expected.begin(), expected.end());
  BOOST_REQUIRE_EQUAL(traces.lines.size(), 1u);  // reported once per block
  BOOST_CHECK(traces.lines[0].find("inbox full (2 events, 4 bytes)") != std::string::npos);
}

namespace {

void quitter(vs_ctx* c) { note(c, "started and done"); }

}  // namespace

BOOST_AUTO_TEST_CASE(a_block_whose_loop_returns_ignores_its_events) {
  const vs_polling_program program{"quitter", quitter, 0, 0, 0, 0, nullptr};
  vs_blockcode table;
  auto sim = prepare(program, {3, 1, 1}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, table);
  sim->scheduleTap(1, kSecond);
  sim->runUntilEmpty();
  BOOST_CHECK_EQUAL(gLog.size(), 3u);  // each block's loop ran once; the tap found block 1 done
  BOOST_CHECK_EQUAL(sim->statistics().eventsByKind[std::size_t(EventKind::Tap)], 1u);
}

BOOST_AUTO_TEST_CASE(bad_arguments_are_refused) {
  static int codes[5];
  const vs_polling_program program{"bad", [](vs_ctx* c) {
                                      vs_event ev;
                                      codes[0] = vs_wait(c, 0, VS_FOREVER, &ev);
                                      codes[1] = vs_wait(c, VS_WAIT_KIND(VS_EV_TAP), -5, &ev);
                                      codes[2] = vs_wait(c, VS_WAIT_KIND(VS_EV_TAP), 0, nullptr);
                                      codes[3] = vs_sleep(c, -1);
                                      codes[4] = vs_wait_sensor(c, 0, 0, &ev);
                                    },
                                   0, 0, 0, 0, nullptr};
  vs_blockcode table;
  auto sim = run(program, {1, 1, 1}, {{0, 0, 0}}, table);
  for (int rc : codes) BOOST_CHECK_EQUAL(rc, VS_ERR_BAD_ARGUMENT);
}

namespace {

struct Counter {
  std::uint32_t woken;
};

// Many blocks, each waking every 10 ms for 1 s: the program's own state survives the switches.
void ticker(vs_ctx* c) {
  Counter* s = static_cast<Counter*>(c->state);
  while (vs_now(c) < VS_S) {
    vs_sleep(c, 10 * VS_MS);
    ++s->woken;
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(state_survives_and_runs_are_deterministic) {
  const vs_polling_program program{"ticker", ticker, sizeof(Counter), 4096, 0, 0, nullptr};
  std::vector<Cell> cells;
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y) cells.push_back(Cell{x, y, 0});
  std::uint64_t prints[2];
  for (int i = 0; i < 2; ++i) {
    vs_blockcode table;
    auto sim = run(program, {20, 20, 1}, cells, table);
    // The program's state is the last 16 bytes of each block's (after stack, record and inbox).
    for (BlockId b = 0; b < cells.size(); ++b)
      BOOST_CHECK_EQUAL(
          reinterpret_cast<Counter*>(static_cast<char*>(sim->blockState(b)) + table.state_size - 16)->woken, 100u);
    prints[i] = sim->fingerprint();
  }
  BOOST_CHECK_EQUAL(prints[0], prints[1]);
}

namespace {

// Frames that fill all their bytes, as a real overflow (a big local array in use) would.
[[gnu::noinline]] int depth(int n) {
  char pad[512];
  std::memset(pad, n, sizeof pad);
  __asm__ volatile("" : : "r"(pad) : "memory");
  return n == 0 ? pad[7] : depth(n - 1) + pad[n];
}

// Block 1 of three recurses through some 6 KB on a 4 KB stack: past its guard words, into the state
// of block 0 below it, never into its own record.
void overflow(vs_ctx* c) {
  if (c->block == 1) note(c, std::to_string(depth(10)));
  vs_sleep(c, VS_MS);
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_stack_overflow_is_reported_with_the_block_and_the_size) {
  int pipefd[2];
  BOOST_REQUIRE_EQUAL(pipe(pipefd), 0);
  const pid_t child = fork();
  BOOST_REQUIRE(child >= 0);
  if (child == 0) {
    dup2(pipefd[1], 2);
    std::signal(SIGABRT, SIG_DFL);  // Boost.Test's handler would turn the abort into a report
    const vs_polling_program program{"overflow", overflow, 0, 4096, 0, 0, nullptr};
    vs_blockcode table;
    auto sim = run(program, {3, 1, 1}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, table);
    _exit(0);
  }
  close(pipefd[1]);
  std::string err;
  char buf[256];
  for (ssize_t n; (n = read(pipefd[0], buf, sizeof buf)) > 0;) err.append(buf, std::size_t(n));
  close(pipefd[0]);
  int status = 0;
  waitpid(child, &status, 0);
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer, which polling.c tells of each block's stack at every switch, ASan may
  // catch the overflow first, as it happens (the x86-64 switch), or the guard words do (ucontext):
  // either way the child stops with a report of the overflow.
  BOOST_CHECK(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0));
  BOOST_CHECK_MESSAGE(err.find("AddressSanitizer: stack-overflow") != std::string::npos ||
                          err.find("vs_polling: block 1 of program 'overflow' overflowed its 4096-byte stack") !=
                              std::string::npos,
                      err);
#else
  BOOST_CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT);
  BOOST_CHECK_MESSAGE(err.find("vs_polling: block 1 of program 'overflow' overflowed its 4096-byte stack") !=
                          std::string::npos,
                      err);
#endif
}
