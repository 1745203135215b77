#include "block_history.hpp"

#include <algorithm>
#include <iterator>

#include "meldvm/dump.hpp"
#include "simcore/trace.hpp"

namespace ide {

BlockHistory::BlockHistory(vsim::Session& session, simcore::BlockId block)
    : session_(session), block_(block), facts_(currentFacts()), lastEventTime_(session.simulation().now()) {}

std::vector<std::string> BlockHistory::currentFacts() const {
  std::vector<std::string> out;
  const meldvm::BlockRuntime* meld = session_.meld();
  if (!meld) return out;
  for (meldvm::PredicateFacts& g : meldvm::nodeFacts(meld->machine().database(), meldvm::NodeId(block_)))
    for (std::string& l : g.lines) out.push_back(std::move(l));
  std::sort(out.begin(), out.end());
  return out;
}

void BlockHistory::add(simcore::SimTime t, std::string text) {
  entries_.push_back(HistoryEntry{t, std::move(text)});
  if (entries_.size() > kMaxEntries) entries_.pop_front();
}

void BlockHistory::flush() {
  if (!session_.meld()) return;
  std::vector<std::string> now = currentFacts();
  if (now == facts_) return;
  std::vector<std::string> gone, added;
  std::set_difference(facts_.begin(), facts_.end(), now.begin(), now.end(), std::back_inserter(gone));
  std::set_difference(now.begin(), now.end(), facts_.begin(), facts_.end(), std::back_inserter(added));
  for (std::string& f : gone) add(lastEventTime_, "- " + f);
  for (std::string& f : added) add(lastEventTime_, "+ " + f);
  facts_ = std::move(now);
}

void BlockHistory::onEvent(const simcore::Simulation& sim, const simcore::Event& e) {
  if (e.block != block_) return;
  flush();  // what the block's previous event changed
  lastEventTime_ = e.time;
  if (e.kind == simcore::EventKind::Message) {
    // Called before delivery, with the link intact: the sender is the neighbour on that face.
    const simcore::BlockId from = sim.world().neighbor(e.block, e.face);
    add(e.time, "received a message on face " + sim.target().faceNames[e.face] + " from block " +
                    (from == simcore::kNoBlock ? std::string("?") : std::to_string(from)));
  } else {
    add(e.time, std::string("event ") + simcore::eventKindName(e.kind));
  }
}

void BlockHistory::onMessageSent(const simcore::Simulation& sim, std::uint32_t from, int face,
                                 std::uint32_t to, std::uint32_t size, simcore::SimTime arrival) {
  if (from != block_) return;
  add(sim.now(), "sent " + std::to_string(size) + " bytes on face " +
                     sim.target().faceNames[std::size_t(face)] + " to block " + std::to_string(to) +
                     " (arrives at " + simcore::formatTime(arrival) + ")");
}

}  // namespace ide
