// The history of the selected block, recorded only while the inspector shows it (a big run with
// nothing selected pays nothing): the facts its node gained and lost at each of its events, and
// the messages it sent and received, with simulated times. Facts are found by comparing the
// block's facts between its own events: only its events change them, so each difference belongs
// to the event before, and the VM's hot paths are not touched.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "session.hpp"
#include "simcore/observer.hpp"
#include "snapshot.hpp"

namespace ide {

class BlockHistory final : public simcore::SimulationObserver {
 public:
  static constexpr std::size_t kMaxEntries = 5000;
  BlockHistory(vsim::Session& session, simcore::BlockId block);

  void onEvent(const simcore::Simulation& sim, const simcore::Event& e) override;
  void onMessageSent(const simcore::Simulation& sim, std::uint32_t from, int face, std::uint32_t to,
                     std::uint32_t size, simcore::SimTime arrival) override;
  // Notes what changed since the block's last event (before a snapshot is made).
  void flush();
  simcore::BlockId block() const { return block_; }
  const std::deque<HistoryEntry>& entries() const { return entries_; }

 private:
  std::vector<std::string> currentFacts() const;
  void add(simcore::SimTime t, std::string text);

  vsim::Session& session_;
  simcore::BlockId block_;
  std::vector<std::string> facts_;      // sorted, as of the last look
  simcore::SimTime lastEventTime_ = 0;  // the block's event the next differences belong to
  std::deque<HistoryEntry> entries_;
};

}  // namespace ide
