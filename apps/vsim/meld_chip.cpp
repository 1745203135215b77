#include "meld_chip.hpp"

#include "meldvm/program_tables.hpp"
#include "meldvm/shard_set.hpp"

namespace vsim {

using meldvm::NodeId;
using meldvm::ThreadId;

// One core's shard and its side of the link: facts for other cores collect in one buffer per
// destination core until the node run ends.
class MeldChip::CoreShard final : public meldvm::ShardLink {
 public:
  CoreShard(MeldChip& chip, meldvm::MachineOptions options, ThreadId self)
      : chip_(chip), outgoing_(chip.directory_->threads()), facts_(chip.directory_->threads()) {
    options.shard = this;
    options.stopFlag = &chip.stop_;
    const meldvm::threads::NodeDirectory& d = *chip.directory_;
    options.placement = {self, d.threads(), d.firstOwned(self), d.endOwned(self)};
    machine = std::make_unique<meldvm::Machine>(chip.program_, std::move(options));
  }

  ThreadId ownerOf(NodeId n) const override { return chip_.directory_->ownerOf(n); }
  const meldvm::NodeOwners* graphOwners() const override { return &chip_.directory_->graphOwners(); }
  void sendRemote(ThreadId to, NodeId dest, meldvm::PredId p, const meldvm::Value* args,
                  bool negative) override {
    const std::size_t before = outgoing_[to].size();
    chip_.mail_.putFact(outgoing_[to], machine->heap(), dest, p, args, negative);
    bytes_ += outgoing_[to].size() - before;
    ++facts_[to];
  }
  void coordinateRemote(ThreadId to, meldvm::Opcode op, NodeId n, double value) override {
    const std::size_t before = outgoing_[to].size();
    chip_.mail_.putCoordination(outgoing_[to], n, op, value);
    bytes_ += outgoing_[to].size() - before;
    ++facts_[to];
  }
  // Whether the batches go now (meldvm::BatchPolicy, as the worker threads send them); called
  // once per node run.
  bool flushDue(bool force) {
    if (bytes_ == 0) return false;
    if (force || bytes_ >= meldvm::BatchPolicy::kFlushBytes ||
        ++runsSinceFlush_ >= meldvm::BatchPolicy::kFlushRuns)
      return true;
    return false;
  }
  NodeId allocateNodeBlock(ThreadId self, NodeId& count) override {
    return chip_.directory_->allocateBlock(self, count);
  }
  void requestMove(NodeId n, ThreadId to) override { chip_.moves_.emplace_back(n, to); }
  void stopAll() override { chip_.stop_.store(true, std::memory_order_relaxed); }
  void staticChanged(ThreadId t, int delta) override { chip_.staticNodes_[t] += delta; }
  std::int32_t staticNodes(ThreadId t) const override {
    return t < chip_.staticNodes_.size() ? chip_.staticNodes_[t] : 0;
  }

  // Hands the buffers that hold something to `take(to, facts, bytes)` and empties them.
  template <class Take>
  void drain(Take&& take) {
    for (ThreadId to = 0; to < outgoing_.size(); ++to) {
      if (outgoing_[to].empty()) continue;
      take(to, facts_[to], outgoing_[to]);
      outgoing_[to].clear();
      facts_[to] = 0;
    }
    bytes_ = 0;
    runsSinceFlush_ = 0;
  }

  std::unique_ptr<meldvm::Machine> machine;

 private:
  MeldChip& chip_;
  std::vector<meldvm::MailBytes> outgoing_;
  std::vector<std::uint64_t> facts_;
  std::size_t bytes_ = 0;
  unsigned runsSinceFlush_ = 0;
};

MeldChip::MeldChip(const meldvm::Program& program, meldvm::MachineOptions options, unsigned cores)
    : program_(program), mail_(program), staticNodes_(cores, 0) {
  if (cores == 0 || cores > 1024) throw std::invalid_argument("a chip has 1 to 1024 cores");
  if (options.host) throw std::invalid_argument("a chip drives its own nodes (no host)");
  const NodeId graph = std::max<NodeId>(NodeId(program.nodeSourceIds.size()), options.nodes);
  const meldvm::ProgramTables tables(program);
  directory_ = std::make_unique<meldvm::threads::NodeDirectory>(program, graph, cores, tables.hasThreads);
  mailSlabs_ = std::make_unique<meldvm::MailSlabs>(cores);
  options.mailSlabs = mailSlabs_.get();
  for (ThreadId c = 0; c < cores; ++c) cores_.push_back(std::make_unique<CoreShard>(*this, options, c));
}

MeldChip::~MeldChip() {
  // The shards hold references to each other's heap objects: all let go before any heap goes.
  for (auto& c : cores_) c->machine->releaseAll();
}

multicore::Work MeldChip::workSince(unsigned core, const meldvm::MachineStats& before) const {
  const meldvm::MachineStats& now = cores_[core]->machine->stats();
  return {now.rulesFired - before.rulesFired, now.factsDerived - before.factsDerived,
          now.factsTried - before.factsTried};
}

multicore::Work MeldChip::start(unsigned core) {
  const meldvm::MachineStats before = cores_[core]->machine->stats();
  cores_[core]->machine->start();
  return workSince(core, before);
}

bool MeldChip::runNext(unsigned core, multicore::Work& work) {
  meldvm::Machine& m = *cores_[core]->machine;
  const meldvm::MachineStats before = m.stats();
  if (!m.runNext()) return false;
  work = workSince(core, before);
  return true;
}

std::size_t MeldChip::queued(unsigned core) const { return cores_[core]->machine->waitingNodes(); }

void MeldChip::takeOutgoing(unsigned core, std::vector<multicore::Batch>& out, bool force) {
  if (!cores_[core]->flushDue(force)) return;
  cores_[core]->drain([&](ThreadId to, std::uint64_t facts, meldvm::MailBytes& bytes) {
    std::uint64_t handle;
    if (freeBatches_.empty()) {
      handle = batches_.size();
      batches_.emplace_back();
    } else {
      handle = freeBatches_.back();
      freeBatches_.pop_back();
    }
    batches_[handle].swap(bytes);  // the emptied buffer of an earlier batch goes back to the core
    out.push_back({to, facts, batches_[handle].size(), handle});
  });
}

void MeldChip::deliver(unsigned core, std::uint64_t handle) {
  meldvm::ShardMail::Taken taken;
  mail_.apply(*cores_[core]->machine, batches_[handle], taken);
  batches_[handle].clear();
  freeBatches_.push_back(handle);
}

std::uint64_t MeldChip::moveNode(unsigned from, unsigned to, NodeId n, bool moved) {
  moving_.clear();
  mail_.putNode(moving_, *cores_[from]->machine, n, moved);
  directory_->moveNode(n, to);
  meldvm::ShardMail::Taken taken;
  mail_.apply(*cores_[to]->machine, moving_, taken);
  return moving_.size();
}

std::size_t MeldChip::moveNodes(unsigned from, unsigned to, std::size_t count, std::uint64_t& bytes) {
  const std::vector<NodeId> nodes = cores_[from]->machine->pickNodesToGive(count, to > from);
  for (NodeId n : nodes) bytes += moveNode(from, to, n, false);
  return nodes.size();
}

std::size_t MeldChip::applyRequestedMoves(std::uint64_t& bytes) {
  std::size_t moved = 0;
  for (const auto& [n, to] : moves_) {
    const ThreadId from = directory_->ownerOf(n);
    if (from == to || from == meldvm::kNoThread || !cores_[from]->machine->unqueueToGive(n)) continue;
    bytes += moveNode(from, to, n, true);
    ++moved;
  }
  moves_.clear();
  return moved;
}

bool MeldChip::stealable() const { return !program_.scheduling.staticNodes; }

std::vector<const meldvm::Machine*> MeldChip::shards() const {
  std::vector<const meldvm::Machine*> all;
  for (const auto& c : cores_) all.push_back(c->machine.get());
  return all;
}

void MeldChip::finish() {
  if (stopped()) return;
  std::vector<meldvm::Machine*> all;
  for (auto& c : cores_) all.push_back(c->machine.get());
  meldvm::collectGarbageNodes(all);
}

std::string MeldChip::dump() const { return meldvm::dumpShards(program_, *directory_, shards()); }

meldvm::MachineStats MeldChip::stats() const { return meldvm::sumStats(shards()); }

std::size_t MeldChip::bytesInUse() const {
  std::size_t b = 0;
  for (const auto& c : cores_) b += c->machine->bytesInUse();
  return b;
}

}  // namespace vsim
