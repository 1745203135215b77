// What the kernel needs to know about a kind of robot. Targets (targets/) fill one in; the kernel
// knows nothing else about them.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simcore/lattice.hpp"
#include "simcore/time.hpp"

namespace simcore {

struct LinkModel {
  double rateBitsPerSecond = 1e6;  // transmission time = size * 8 / rate
  SimTime latency = 0;             // added after transmission
  SimTime jitter = 0;              // uniform extra delay in [0, jitter]; never reorders a link
};

struct TargetSpec {
  std::string name;  // "blinkyblocks", "smartblocks"
  std::function<std::unique_ptr<Lattice>()> makeLattice;
  std::vector<std::string> faceNames;  // index = face number
  LinkModel link;
  bool canTranslate = false;  // translation to an adjacent free cell through a face
  SimTime motionDuration = kSecond;
  bool hasTap = false;
  bool hasAccelerometer = false;
  bool hasDisplayValue = false;
  double blockSizeMm = 40.0;
  std::uint32_t defaultColor = 0x808080;
};

}  // namespace simcore
