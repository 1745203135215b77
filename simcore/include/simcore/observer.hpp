// The one notification interface through which front ends (vsim, the IDE, traces) watch a run.
// The kernel calls observers only when at least one is attached.
#pragma once

#include <cstdint>
#include <string_view>

#include "simcore/event.hpp"
#include "simcore/lattice.hpp"

namespace simcore {

class Simulation;

class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  // Whether onEvent and onMessageSent are wanted: they come once per event and per message, so an
  // observer that does not want them (a console showing only the programs' own text) costs the
  // kernel nothing per event. Asked once, when the observer is added.
  virtual bool wantsEvents() const { return true; }
  virtual bool wantsMessages() const { return true; }
  // Called before the event is handed to the block program.
  virtual void onEvent(const Simulation&, const Event&) {}
  virtual void onMessageSent(const Simulation&, std::uint32_t /*from*/, int /*face*/, std::uint32_t /*to*/,
                             std::uint32_t /*size*/, SimTime /*arrival*/) {}
  // A message in flight was lost because its link broke.
  virtual void onMessageDropped(const Simulation&, std::uint32_t /*from*/, int /*face*/,
                                std::uint32_t /*to*/) {}
  virtual void onColorChanged(const Simulation&, std::uint32_t /*block*/, std::uint32_t /*rgb*/) {}
  virtual void onMotionStarted(const Simulation&, std::uint32_t /*block*/, const Cell& /*from*/,
                               const Cell& /*to*/, SimTime /*end*/) {}
  // Text from the block program's trace service.
  virtual void onBlockTrace(const Simulation&, std::uint32_t /*block*/, std::string_view /*text*/) {}
  // After each step of the physics (Simulation::physics()), mobiles moved.
  virtual void onPhysicsStep(const Simulation&) {}
};

}  // namespace simcore
