// What the GUI draws and shows: an immutable copy of the run's state, made by the kernel thread
// between slices of events and handed over whole. The GUI never reads the simulation itself.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "meldvm/derivation_log.hpp"
#include "simcore/lattice.hpp"
#include "simcore/time.hpp"
#include "simcore/world.hpp"

namespace ide {

enum class RunState : std::uint8_t {
  Paused,    // waiting for a command (also at the start)
  Running,   // running paced or as fast as possible
  Finished,  // the event queue is empty: the run is over (the fingerprint is final)
  Failed,    // the block program or the kernel stopped with an error (`error` says which)
};
const char* runStateName(RunState s);

struct FactGroup {
  std::string predicate;
  bool persistent = false;
  std::vector<std::string> lines;  // as `--dump` prints them, sorted
};

struct HistoryEntry {
  simcore::SimTime time = 0;
  std::string text;  // "+ !dist(2)", "- tap()", "sent 9 bytes on face top to block 3 ...", ...
};

// Why a fact exists, as the kernel found it (meldvm::whyTree) for the last fact asked about.
struct WhyResult {
  std::uint64_t request = 0;  // SimController::why's number
  simcore::BlockId block = simcore::kNoBlock;
  std::string fact;                    // as the dump prints it
  std::vector<meldvm::WhyLine> lines;  // empty: `error` says why
  std::string error;
};

struct BlockDetails {
  simcore::BlockId id = simcore::kNoBlock;  // kNoBlock: nothing selected
  simcore::Cell cell;
  std::uint32_t color = 0;
  bool alive = false, moving = false;
  std::vector<std::pair<std::string, simcore::BlockId>> neighbors;  // face name, block (or kNoBlock)
  std::vector<FactGroup> facts;       // Meld programs: the block's node, grouped as the dump
  std::string info;                   // C BlockCodes: the text of the info callback
  std::vector<HistoryEntry> history;  // while the inspector asks for it (SimController::setHistory)
};

struct WorldSnapshot {
  std::uint64_t serial = 0;   // increases with every snapshot of a session
  std::uint64_t session = 0;  // increases with every (re)start
  simcore::SimTime now = 0;
  std::uint64_t events = 0;
  double eventsPerSecond = 0;  // events over the kernel's wall time since the run started
  std::size_t pendingEvents = 0;
  RunState state = RunState::Paused;
  std::uint64_t fingerprint = 0;
  std::string error;
  // Per block, index = block id; positions in mm (interpolated during motions). As in VisibleSim's
  // worlds, cell (x, y, z) spans [x, x + 1) block sizes: the floor is z = 0 and the grid starts at
  // the origin, so a <camera target> of the world file's looks where it should.
  std::vector<std::array<float, 3>> positions;
  std::vector<std::uint32_t> colors;
  std::vector<std::uint8_t> alive;
  BlockDetails selected;
  std::shared_ptr<const WhyResult> why;  // the last answer of SimController::why, if any
};

}  // namespace ide
