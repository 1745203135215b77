// One worker thread of a threaded run: its shard (a Machine), the facts it has for other threads
// until they go out in a batch, and the loop that runs nodes, takes in facts and waits.
#pragma once

#include <chrono>
#include <memory>
#include <ostream>
#include <thread>
#include <vector>

#include "line_output.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/node_directory.hpp"
#include "meldvm/shard_mail.hpp"
#include "meldvm/threaded_machine.hpp"
#include "profile_recorder.hpp"
#include "shared_state.hpp"
#include "support/steal_policy.hpp"

namespace meldvm::threads {

// Cache lines of its own: its thread writes its counters all the time, and the Worker allocated
// next to it is read (vtable, directory) by another thread on the facts that thread sends elsewhere
// (false sharing: on B2 shortest-path at -j 2, a quarter of the owner look-up's samples sat on
// such a read).
class alignas(64) Worker final : public ShardLink {
 public:
  Worker(const Program& program, MachineOptions options, ThreadId self, NodeDirectory& directory,
         SharedState& shared, std::mutex& outputLock);
  ~Worker() override;

  void launch() {
    thread_ = std::thread([this] { loop(); });
  }
  void join() {
    if (thread_.joinable()) thread_.join();
  }
  Machine& machine() { return *machine_; }
  const Machine& machine() const { return *machine_; }
  // The machine's memory, with the batches this thread sends and takes in counted as buffers.
  MemoryUse memoryUse() const;
  ThreadStats stats() const;
  // Records a timeline of this thread's run (before launch()).
  void recordProfile(std::chrono::steady_clock::time_point origin) {
    profile_ = std::make_unique<ProfileRecorder>(origin);
  }
  const ProfileRecorder* profile() const { return profile_.get(); }

  // ShardLink.
  ThreadId ownerOf(NodeId n) const override { return directory_.ownerOf(n); }
  const NodeOwners* graphOwners() const override { return &directory_.graphOwners(); }
  void sendRemote(ThreadId to, NodeId dest, PredId p, const Value* args, bool negative) override;
  void coordinateRemote(ThreadId to, Opcode op, NodeId n, double value) override;
  NodeId allocateNodeBlock(ThreadId self, NodeId& count) override {
    return directory_.allocateBlock(self, count);
  }
  void stopAll() override { shared_.stopAll(); }
  void safePoint() override;
  void requestMove(NodeId n, ThreadId to) override;
  void staticChanged(ThreadId t, int delta) override { shared_.perThread[t].staticNodes.fetch_add(delta); }
  std::int32_t staticNodes(ThreadId t) const override {
    return t < shared_.threads ? shared_.perThread[t].staticNodes.load() : 0;
  }

 private:
  static constexpr std::size_t kFlushBytes = BatchPolicy::kFlushBytes;
  static constexpr unsigned kFlushRuns = BatchPolicy::kFlushRuns;

  void loop();
  bool takeMail();  // takes in every batch waiting for this thread; false if there was none
  bool takeFrom(ThreadId from);  // what the channel from that thread holds; false if nothing
  void takeGivenNodes();
  bool mailWaiting() const;
  void decode(const Bytes& records);
  void flush();
  bool waitForWork();  // false: the run is over (quiescence, stop-program or an error)
  // Work stealing (see worker.cpp): ask for a rebalance when out of work while another thread
  // has a long queue; take part in one.
  bool requestRebalance();
  void offerWork();
  void rebalance(bool midRun = false);  // midRun: from a safe point of a node run
  void planMoves();                     // phase 3 of a rebalance
  void publishIdleShare(std::chrono::steady_clock::time_point arrived,
                        std::chrono::steady_clock::time_point allThere);
  void giveNodes(ThreadId to, std::size_t count);
  void giveNode(ThreadId to, NodeId n, bool moved);  // moved: by set-cpu (pin it, just-moved)
  static constexpr std::uint32_t kStealableQueue = support::StealPolicy::kStealableQueue;

  const Program& program_;
  const ThreadId self_;
  NodeDirectory& directory_;
  SharedState& shared_;
  std::unique_ptr<LineOutput> lineOutput_;
  std::unique_ptr<std::ostream> output_;
  std::unique_ptr<Machine> machine_;
  std::vector<Bytes> outgoing_;  // per destination thread
  std::size_t outgoingBytes_ = 0;
  unsigned runsSinceFlush_ = 0;
  Bytes incoming_;
  RecentBatches recentBatches_;  // sent and taken: how much memory the batch buffers keep
  const bool stealing_;  // not with `priority @static`
  ShardMail mail_;
  std::vector<std::pair<NodeId, ThreadId>> deferredMoves_;  // set-cpu of the node running at a safe point
  ThreadStats stats_;
  // Since the last rebalance (or the start): the idle share a rebalance weighs.
  std::chrono::steady_clock::time_point windowStart_;
  double idleAtWindowStart_ = 0;
  std::unique_ptr<ProfileRecorder> profile_;
  std::thread thread_;
};

}  // namespace meldvm::threads
