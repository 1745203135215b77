// Looking targets up by the names used on the command line and in XML worlds.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "simcore/target_spec.hpp"

namespace targets {

// "blinkyblocks" / "BlinkyBlocks" / "bb", "smartblocks" / "SmartBlocks" / "sb", "catoms2d" /
// "Catoms2D" / "c2d", "catoms3d" / "Catoms3D" / "c3d" (case-insensitive).
std::optional<simcore::TargetSpec> makeTarget(std::string_view name);
std::vector<std::string> targetNames();

}  // namespace targets
