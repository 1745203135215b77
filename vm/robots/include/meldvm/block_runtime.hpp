// The Meld VM as a block program (spec §7.3): one Meld node per simulated block (node id = block
// id), all sharing one Program and one fact store. The simulator cannot tell it from a C BlockCode:
// it is a vs_blockcode table whose callbacks
//   - assert and retract the sensing facts of §7.1 as the world changes (neighbor, vacant,
//     neighborCount, at; linear tap, accel, shake),
//   - turn a fact derived for another block into a message on the face leading to it (its size is
//     the encoded fact, fact_codec.hpp), and a delayed fact (`@+Nms`) into a timer,
//   - execute the action facts of §7.2 (setColor/setColor2/setcolor, moveTo, terminate),
//   - and run the block's node until it has nothing left to do after every event.
// Execution time model: the facts a node run sends leave after `rulesFired * timePerRule` of
// simulated computing time, so long computations delay a block's messages.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "meldvm/derivation_log.hpp"
#include "meldvm/fact_codec.hpp"
#include "meldvm/machine.hpp"
#include "meldvm/program.hpp"
#include "meldvm/robot_program.hpp"
#include "simcore/blockcode.h"

namespace meldvm {

enum class Palette : std::uint8_t {
  VisibleSim,  // setColor2(C): C mod 12 into red, orange, yellow, green, cyan, blue, white,
               // magenta, pink, gold, brown, grey
  LinearMeld,  // setColor2(C): 0 red, 1 orange, 2 yellow, 3 green, 4 aqua, 5 blue, 6 white,
               // 7 purple, 8 pink; other values leave the colour unchanged
};

struct BlockRuntimeOptions {
  std::vector<std::string> args;      // @arg1 ...
  std::ostream* output = nullptr;     // write-string
  std::int64_t timePerRuleNs = 1000;  // simulated computing time of one rule firing
  Palette palette = Palette::VisibleSim;
  // How many neighbor and vacant facts the world will start with (all blocks together), so that
  // their tables are allocated once at the right size; 0 = unknown.
  std::size_t neighborFacts = 0, vacantFacts = 0;
  const NativeCode* native = nullptr;  // native code of the program's blocks (must outlive the runtime)
};

class BlockRuntime : private MachineHost {
 public:
  // Checks that the sensing/action predicates the program declares have the shapes of §7 and that
  // every node literal of the program is a block (node ids = block ids); throws BlockProgramError.
  BlockRuntime(const Program& program, std::uint32_t blockCount, BlockRuntimeOptions options = {});
  ~BlockRuntime() override;

  // The block program to hand to the simulator; valid as long as this object.
  const vs_blockcode* blockcode() const { return &code_; }

  const Machine& machine() const { return *machine_; }
  // Why a fact exists: from now on the VM notes where each fact comes from, with simulated times,
  // and the sensed facts as such (nullptr: stop). The log must outlive this runtime or the next call.
  void recordDerivations(DerivationLog* log);
  void dump(std::ostream& out) const { machine_->dump(out); }
  // The first error raised on a block (the run should stop), or empty.
  const std::string& error() const { return error_; }
  std::uint64_t messageBytes() const { return messageBytes_; }
  std::uint64_t messages() const { return messages_; }

 private:
  using Sensing = RobotPredicates;  // predicate ids of §7, resolved once
  struct BlockState;

  static void onStart(vs_ctx* ctx);
  static void onEvent(vs_ctx* ctx, const vs_event* ev);
  static int onInfo(vs_ctx* ctx, char* text, size_t capacity);

  void start(vs_ctx* ctx);
  void event(vs_ctx* ctx, const vs_event& ev);
  void assertSensors(vs_ctx* ctx);
  void sense(NodeId n, PredId p, std::initializer_list<std::int32_t> ints, bool negative);
  void receiveSensed(NodeId n, PredId p, const Value* args, bool negative);
  void retractInverseRoutes(NodeId n, NodeId other);
  void runNode(vs_ctx* ctx);
  void failed(vs_ctx* ctx, const std::exception& e);

  // MachineHost
  void transmit(NodeId from, NodeId to, PredId p, const Value* args, bool negative,
                std::uint32_t delayMs) override;
  void action(NodeId from, NodeId to, PredId p, const Value* args) override;
  bool reachable(NodeId from, NodeId to) override;

  const Program& program_;
  BlockRuntimeOptions options_;
  std::unique_ptr<Machine> machine_;
  std::unique_ptr<Sensing> sensing_;
  vs_blockcode code_;
  vs_ctx* ctx_ = nullptr;  // the callback being served
  std::uint64_t firedInRun_ = 0;
  std::string error_;
  std::vector<std::uint8_t> buffer_;
  DecodedFact decoded_;
  std::uint64_t messageBytes_ = 0, messages_ = 0;
  // Delayed facts for the block itself, waiting for their timer (tag = index).
  std::vector<std::vector<std::uint8_t>> delayed_;
  std::vector<std::uint32_t> freeDelayed_;
  // retractInverseRoutes' copies of the stale facts and their counts (kept: no allocation per break)
  std::vector<Value> retracting_;
  std::vector<std::uint32_t> retractingCopies_;
};

}  // namespace meldvm
