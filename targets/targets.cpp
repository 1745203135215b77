#include "targets.hpp"

#include <algorithm>
#include <cctype>

#include "blinkyblocks/blinkyblocks.hpp"
#include "catoms2d/catoms2d.hpp"
#include "catoms3d/catoms3d.hpp"
#include "smartblocks/smartblocks.hpp"

namespace targets {

std::optional<simcore::TargetSpec> makeTarget(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (n == "blinkyblocks" || n == "blinkyblock" || n == "bb") return blinkyBlocksTarget();
  if (n == "smartblocks" || n == "smartblock" || n == "sb") return smartBlocksTarget();
  if (n == "catoms2d" || n == "c2d") return catoms2DTarget();
  if (n == "catoms3d" || n == "c3d") return catoms3DTarget();
  return std::nullopt;
}

std::vector<std::string> targetNames() { return {"blinkyblocks", "smartblocks", "catoms2d", "catoms3d"}; }

}  // namespace targets
