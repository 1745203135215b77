#include "meldvm/threaded_machine.hpp"

#include <chrono>
#include <sstream>

#include "meldvm/node_directory.hpp"
#include "meldvm/shard_set.hpp"
#include "shared_state.hpp"
#include "worker.hpp"

namespace meldvm {

ThreadedMachine::ThreadedMachine(const Program& program, MachineOptions options, unsigned threads)
    : program_(program) {
  if (threads == 0) throw std::invalid_argument("a threaded run needs at least one thread");
  if (options.host) throw std::invalid_argument("a threaded run drives its own nodes (no host)");
  const NodeId graph = std::max<NodeId>(NodeId(program.nodeSourceIds.size()), options.nodes);
  const ProgramTables tables(program);
  directory_ = std::make_unique<threads::NodeDirectory>(program, graph, threads, tables.hasThreads);
  shared_ = std::make_unique<threads::SharedState>(threads);
  mailSlabs_ = std::make_unique<MailSlabs>(threads);
  options.mailSlabs = mailSlabs_.get();
  for (ThreadId t = 0; t < threads; ++t)
    workers_.push_back(
        std::make_unique<threads::Worker>(program, options, t, *directory_, *shared_, outputLock_));
}

ThreadedMachine::~ThreadedMachine() {
  for (auto& w : workers_) w->join();
  // The shards hold references to each other's heap objects: all let go before any heap goes.
  for (auto& w : workers_) w->machine().releaseAll();
}

void ThreadedMachine::run() {
  const auto start = std::chrono::steady_clock::now();
  if (profile_)
    for (auto& w : workers_) w->recordProfile(start);
  for (auto& w : workers_) w->launch();
  for (auto& w : workers_) w->join();
  wallSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (shared_->error) std::rethrow_exception(shared_->error);
  if (!stopped()) collectGarbageNodes();
}

bool ThreadedMachine::stopped() const { return shared_->stop.load(); }

void ThreadedMachine::cancel() { shared_->stopAll(); }

std::vector<const Machine*> ThreadedMachine::shards() const {
  std::vector<const Machine*> all;
  for (const auto& w : workers_) all.push_back(&w->machine());
  return all;
}

void ThreadedMachine::collectGarbageNodes() {
  std::vector<Machine*> all;
  for (auto& w : workers_) all.push_back(&w->machine());
  meldvm::collectGarbageNodes(all);
}

void ThreadedMachine::dump(std::ostream& out) const { out << dump(); }

std::string ThreadedMachine::dump() const { return dumpShards(program_, *directory_, shards()); }

MachineStats ThreadedMachine::stats() const { return sumStats(shards()); }

std::vector<ThreadStats> ThreadedMachine::threadStats() const {
  std::vector<ThreadStats> s;
  for (const auto& w : workers_) s.push_back(w->stats());
  return s;
}

MemoryUse ThreadedMachine::memoryUse() const {
  MemoryUse m;
  for (const auto& w : workers_) m += w->memoryUse();
  return m;
}

}  // namespace meldvm
