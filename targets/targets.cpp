#include "targets.hpp"

#include <algorithm>
#include <cctype>

#include "blinkyblocks/blinkyblocks.hpp"
#include "smartblocks/smartblocks.hpp"

namespace targets {

std::optional<simcore::TargetSpec> makeTarget(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (n == "blinkyblocks" || n == "blinkyblock" || n == "bb") return blinkyBlocksTarget();
  if (n == "smartblocks" || n == "smartblock" || n == "sb") return smartBlocksTarget();
  return std::nullopt;
}

std::vector<std::string> targetNames() { return {"blinkyblocks", "smartblocks"}; }

}  // namespace targets
