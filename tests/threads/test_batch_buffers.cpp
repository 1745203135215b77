// How much memory the buffers of the threads' batches keep (meldvm/shard_mail.hpp): a buffer past
// the limit is given back when it is emptied, and the limit follows the thread's recent batches, so
// that large batches in a row reuse one buffer and a few large ones do not pin memory to the end.
#define BOOST_TEST_MODULE threads_batch_buffers
#include <boost/test/unit_test.hpp>

#include "meldvm/shard_mail.hpp"

using namespace meldvm;

namespace {

constexpr std::size_t kKept = BatchPolicy::kKeptBytes;

MailBytes bufferOf(std::size_t bytes) {
  MailBytes b(bytes, 1);
  return b;
}

}  // namespace

BOOST_AUTO_TEST_CASE(an_emptied_buffer_keeps_its_memory_up_to_the_limit_only) {
  MailBytes small = bufferOf(kKept);
  clearBuffer(small);
  BOOST_TEST(small.empty());
  BOOST_TEST(small.capacity() >= kKept);

  MailBytes large = bufferOf(kKept + 1);
  clearBuffer(large);
  BOOST_TEST(large.empty());
  BOOST_TEST(large.capacity() == 0u);

  MailBytes kept = bufferOf(3 * kKept);
  clearBuffer(kept, 4 * kKept);
  BOOST_TEST(kept.empty());
  BOOST_TEST(kept.capacity() >= 3 * kKept);
}

BOOST_AUTO_TEST_CASE(the_limit_starts_at_the_policy_and_never_falls_below_it) {
  RecentBatches recent;
  BOOST_TEST(recent.keptBytes() == kKept);
  for (int i = 0; i < 100; ++i) recent.sent(100);
  BOOST_TEST(recent.keptBytes() == kKept);
}

BOOST_AUTO_TEST_CASE(a_large_batch_raises_the_limit_to_twice_its_size) {
  RecentBatches recent;
  recent.sent(3 * kKept);
  BOOST_TEST(recent.keptBytes() == 6 * kKept);
  recent.sent(5 * kKept);  // a larger one raises it again
  BOOST_TEST(recent.keptBytes() == 10 * kKept);
}

BOOST_AUTO_TEST_CASE(small_batches_bring_the_limit_back_down) {
  RecentBatches recent;
  recent.sent(8 * kKept);
  MailBytes buffer = bufferOf(8 * kKept);
  // The next few small batches keep the large buffer for the next large one ...
  for (int i = 0; i < 3; ++i) recent.sent(10);
  clearBuffer(buffer, recent.keptBytes());
  BOOST_TEST(buffer.capacity() >= 8 * kKept);
  // ... a long run of them gives it back, and the limit returns to the policy's.
  int batches = 0;
  while (recent.keptBytes() > kKept && batches < 1000) {
    recent.sent(10);
    ++batches;
  }
  BOOST_TEST(recent.keptBytes() == kKept);
  BOOST_TEST(batches < 40);
  buffer.resize(8 * kKept);
  clearBuffer(buffer, recent.keptBytes());
  BOOST_TEST(buffer.capacity() == 0u);
}
