// vsim --target multicore: the Meld VM as the workload of a simulated chip
// (targets/multicore/chip_simulator.hpp). Each core owns a shard (a Machine of its own, as each
// worker thread of `meld -j N` does), placed by the threaded runtime's own NodeDirectory (the
// static partition), and the facts, coordination facts and nodes that move between cores are
// the threaded runtime's records (meldvm/shard_mail.hpp): the chip changes when they arrive,
// not what they are.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "meldvm/node_directory.hpp"
#include "meldvm/shard_mail.hpp"
#include "multicore/chip_simulator.hpp"

namespace vsim {

class MeldChip final : public multicore::CoreWorkload {
 public:
  // options as for a Machine (no host); `cores` shards.
  MeldChip(const meldvm::Program& program, meldvm::MachineOptions options, unsigned cores);
  ~MeldChip() override;

  // CoreWorkload.
  multicore::Work start(unsigned core) override;
  bool runNext(unsigned core, multicore::Work& work) override;
  std::size_t queued(unsigned core) const override;
  void takeOutgoing(unsigned core, std::vector<multicore::Batch>& out, bool force) override;
  void deliver(unsigned core, std::uint64_t handle) override;
  std::size_t moveNodes(unsigned from, unsigned to, std::size_t count, std::uint64_t& bytes) override;
  bool movesRequested() const override { return !moves_.empty(); }
  std::size_t applyRequestedMoves(std::uint64_t& bytes) override;
  bool stopped() const override { return stop_.load(std::memory_order_relaxed); }

  // After the run: the created nodes nobody refers to go (§6.10), unless the program stopped.
  void finish();
  std::string dump() const;
  meldvm::MachineStats stats() const;
  std::size_t bytesInUse() const;
  // Whether the program may be stolen from (not with `priority @static`).
  bool stealable() const;

 private:
  class CoreShard;
  multicore::Work workSince(unsigned core, const meldvm::MachineStats& before) const;
  std::uint64_t moveNode(unsigned from, unsigned to, meldvm::NodeId n, bool moved);  // returns its bytes
  std::vector<const meldvm::Machine*> shards() const;

  const meldvm::Program& program_;
  std::unique_ptr<meldvm::threads::NodeDirectory> directory_;
  std::unique_ptr<meldvm::MailSlabs> mailSlabs_;  // outlives the cores' mailboxes
  std::vector<std::unique_ptr<CoreShard>> cores_;
  meldvm::ShardMail mail_;
  std::vector<meldvm::MailBytes> batches_;  // in transit, by handle
  std::vector<std::uint64_t> freeBatches_;
  meldvm::MailBytes moving_;
  std::vector<std::pair<meldvm::NodeId, meldvm::ThreadId>> moves_;  // set-cpu, until the next barrier
  std::vector<std::int32_t> staticNodes_;
  std::atomic<bool> stop_{false};
};

}  // namespace vsim
