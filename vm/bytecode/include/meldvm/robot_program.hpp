// What makes a Program fit to run on robots (spec §7), checked by `meldc --robots` before it writes
// the bytecode and by the block runtime before it runs it.
#pragma once

#include <stdexcept>

#include "meldvm/program.hpp"

namespace meldvm {

// A program unfit for robots, or a run-time error of the program on a block (a fact for a block
// that is not a neighbour, ...): reported by meldc, or by the simulator as the run's error.
class BlockProgramError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The §7 predicates a program declares, resolved by name (kNoPred when it does not mention one).
struct RobotPredicates {
  PredId neighbor, vacant, neighborCount, tap, accel, shake, at;
  PredId setcolor, setcolor2, moveto, terminate, writeString;
  PredId mobileOver, mobileAt, senseMobile, airJet;  // Smart Blocks with mobiles
};

// The one check of a program meant for robots, made by `meldc --robots` and by the runtime alike:
// the sensing/action predicates it declares have the shapes of §7 (the sensed events tap, accel
// and shake may be linear, as in the reference, or persistent, as some VisibleSim programs declare
// them), it has no thread predicates, and its nodes kept their source ids. Throws BlockProgramError.
RobotPredicates checkRobotProgram(const Program& program);

}  // namespace meldvm
