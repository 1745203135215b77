// The check of a program meant for robots (robot_program.hpp).
#include "meldvm/robot_program.hpp"

#include <string>

namespace meldvm {

RobotPredicates checkRobotProgram(const Program& program) {
  const PredicateTable& preds = program.predicates;
  const TypeId I = TypeTable::kInt, N = TypeTable::kNode, F = TypeTable::kFloat;
  auto find = [&](std::initializer_list<const char*> names, std::vector<TypeId> shape,
                  const char* declaration) -> PredId {
    for (const char* name : names) {
      const PredId p = preds.find(name);
      if (p == preds.size()) continue;
      if (preds[p].fields != shape || preds[p].thread)
        throw BlockProgramError(std::string("predicate '") + preds[p].name + "' must be declared as `" +
                                declaration + "` to be sensed or executed by the robot (spec §7)");
      return p;
    }
    return Program::kNoPred;
  };
  RobotPredicates s;
  s.neighbor = find({"neighbor"}, {N, I}, "type route neighbor(node, node, int).");
  s.vacant = find({"vacant"}, {I}, "type vacant(node, int).");
  s.neighborCount = find({"neighborCount"}, {I}, "type neighborCount(node, int).");
  s.tap = find({"tap"}, {}, "type linear tap(node).` or `type tap(node).");
  s.accel = find({"accel"}, {I}, "type linear accel(node, int).` or `type accel(node, int).");
  s.shake = find({"shake"}, {I, I, I},
                 "type linear shake(node, int, int, int).` or `type shake(node, int, int, int).");
  s.at = find({"at"}, {I, I, I}, "type at(node, int, int, int).");
  s.moveto = find({"moveto"}, {I, I, I}, "type linear action moveTo(node, int, int, int).");
  s.terminate = find({"terminate"}, {}, "type linear action terminate(node).");
  // Smart Blocks with mobiles (simcore/physics.hpp).
  s.mobileOver = find({"mobileover"}, {I}, "type mobileOver(node, int).");
  s.mobileAt = find({"mobileat"}, {I, F, F, I}, "type linear mobileAt(node, int, float, float, int).");
  s.senseMobile = find({"sensemobile"}, {}, "type linear action senseMobile(node).");
  s.airJet = find({"airjet"}, {I, F, I}, "type linear action airJet(node, int, float, int).");
  s.setcolor2 = preds.find("setcolor2") == preds.size() ? Program::kNoPred : preds.find("setcolor2");
  s.setcolor = preds.find("setcolor") == preds.size() ? Program::kNoPred : preds.find("setcolor");
  s.writeString = preds.find("write-string") == preds.size() ? Program::kNoPred : preds.find("write-string");

  for (PredId p = 0; p < preds.size(); ++p)
    if (preds[p].thread)
      throw BlockProgramError("thread predicate '" + preds[p].name +
                              "': a robot has no VM threads (§6.12 is for the multicore target)");
  for (std::size_t i = 0; i < program.nodeSourceIds.size(); ++i) {
    if (program.nodeSourceIds[i] != std::int64_t(i))
      throw BlockProgramError("the program was compiled with renumbered nodes (node @" +
                              std::to_string(program.nodeSourceIds[i]) + " became @" + std::to_string(i) +
                              "); on robots node ids are block ids: compile it with `meldc --robots`");
  }
  return s;
}

}  // namespace meldvm
