// From a world description to a running Simulation, and from a Simulation back to a world file.
#include <charconv>
#include <filesystem>
#include <ostream>
#include <pugixml.hpp>

#include "simcore/csg.hpp"
#include "simcore/simulation.hpp"
#include "simcore/physics.hpp"
#include "simcore/xml_world.hpp"

namespace simcore {

namespace {

std::string colorText(std::uint32_t rgb) {
  return std::to_string((rgb >> 16) & 0xFF) + "," + std::to_string((rgb >> 8) & 0xFF) + "," +
         std::to_string(rgb & 0xFF);
}

std::string cellText(const Cell& c) {
  return std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.z);
}

// Why the world refused a block that the description placed (the loader checked the file's own grid,
// but the simulation may have been built with another grid or a lattice with parity rules).
std::string refusal(const World& w, const Cell& c) {
  if (!w.inBounds(c)) return "cell (" + cellText(c) + ") is outside the simulation's grid";
  if (!w.lattice().isValidCell(c))
    return "cell (" + cellText(c) + ") is not a cell of the " + w.lattice().name() + " lattice";
  return "cell (" + cellText(c) + ") is already taken";
}

void checkScheduled(const WorldDescription& d, const Simulation& sim, BlockId block, SourcePos pos,
                    bool supported, const char* what) {
  // Descriptions can be built or edited by code, so the loader's check is repeated here.
  if (block >= sim.world().blockCount())
    throw XmlWorldError(d.path, pos.line, pos.column, "block " + std::to_string(block) + " does not exist");
  if (!supported)
    throw XmlWorldError(d.path, pos.line, pos.column, "target '" + sim.target().name + "' has no " + what);
}

}  // namespace

namespace {

// VisibleSim's loop over the grid: z, then y, then x; a cell is a block when its sample point,
// moved so that the solid's bounding box starts at the grid's corner, is inside.
void addCsgBlocks(const WorldDescription& d, const CsgDescription& c, Simulation& sim) {
  CsgSolid solid = [&] {
    try {
      return CsgSolid::parse(c.content);
    } catch (const CsgError& e) {  // the loader checked it; only a description made by code gets here
      throw XmlWorldError(d.path, c.pos.line, c.pos.column, std::string("<csg content>: ") + e.what());
    }
  }();
  const Lattice& lattice = sim.world().lattice();
  const GridSize g = sim.world().size();
  constexpr std::uint64_t kMaxSampled = std::uint64_t(1) << 28;
  if (std::uint64_t(g.x) * std::uint64_t(g.y) * std::uint64_t(g.z) > kMaxSampled)
    throw XmlWorldError(
        d.path, c.pos.line, c.pos.column,
        "a <csg> solid is sampled at every cell of the grid: at most 2^28 cells, this grid has more");
  CsgBox box = c.boundingBox ? solid.boundingBox() : CsgBox{};
  const Vec3 shift{box.min.x - (c.offset ? 1 : 0), box.min.y - (c.offset ? 1 : 0),
                   box.min.z - (c.offset ? 1 : 0)};
  for (std::int32_t z = 0; z < g.z; ++z)
    for (std::int32_t y = 0; y < g.y; ++y)
      for (std::int32_t x = 0; x < g.x; ++x) {
        const Cell cell{x, y, z};
        if (!lattice.isValidCell(cell) || sim.world().settledAt(cell) != kNoBlock) continue;
        const Vec3 at = lattice.csgPoint(cell);
        std::optional<std::uint32_t> color = c.color;
        if (!solid.inside(Vec3{at.x + shift.x, at.y + shift.y, at.z + shift.z}, color)) continue;
        if (sim.addBlock(cell, color.value_or(sim.target().defaultColor)) == kNoBlock)
          throw XmlWorldError(d.path, c.pos.line, c.pos.column, refusal(sim.world(), cell));
      }
  if (sim.world().blockCount() == 0)
    throw XmlWorldError(d.path, c.pos.line, c.pos.column,
                        "the <csg> solid holds no cell of the grid, and the world has no other block");
}

}  // namespace

namespace {

// The mobiles ride on the blocks' surface: the physics knows each block's centre in mm.
void addPhysics(const WorldDescription& d, Simulation& sim) {
  const SourcePos& at = d.mobiles.front().pos;
  if (!sim.target().canTranslate)
    throw XmlWorldError(d.path, at.line, at.column,
                        "<mobileList>: mobiles ride on a surface of Smart Blocks, not on " + sim.target().name);
  const World& w = sim.world();
  std::vector<Eigen::Vector2d> centres;
  centres.reserve(w.blockCount());
  for (BlockId id = 0; id < w.blockCount(); ++id) {
    const Vec3 c = w.lattice().cellCenter(w.block(id).cell);
    centres.emplace_back(c.x * sim.target().blockSizeMm, c.y * sim.target().blockSizeMm);
  }
  std::vector<MobileSpec> mobiles;
  for (const MobileDescription& m : d.mobiles) mobiles.push_back(m.spec);
  std::vector<ObstacleSpec> obstacles;
  for (const ObstacleDescription& o : d.obstacles) obstacles.push_back(o.spec);
  sim.setPhysics(std::make_unique<Physics>(std::move(centres), std::move(mobiles), std::move(obstacles), d.airJets));
}

}  // namespace

void populateSimulation(const WorldDescription& d, Simulation& sim) {
  // Ids in the schedule are indices in d.blocks; they stay valid only if we number from 0.
  if (sim.world().blockCount() != 0)
    throw XmlWorldError(d.path, 0, 0, "the simulation already has blocks; a world file needs an empty one");
  sim.world().reserveBlocks(d.blocks.size());
  for (const BlockDescription& b : d.blocks)
    if (sim.addBlock(b.cell, b.color.value_or(sim.target().defaultColor)) == kNoBlock)
      throw XmlWorldError(d.path, b.pos.line, b.pos.column, refusal(sim.world(), b.cell));
  if (d.csg) addCsgBlocks(d, *d.csg, sim);
  for (const ScheduledTap& t : d.taps) {
    checkScheduled(d, sim, t.block, t.pos, sim.target().hasTap, "tap sensor");
    sim.scheduleTap(t.block, t.time);
  }
  for (const ScheduledAccel& a : d.accels) {
    checkScheduled(d, sim, a.block, a.pos, sim.target().hasAccelerometer, "accelerometer");
    sim.scheduleAccel(a.block, a.time, a.value[0], a.value[1], a.value[2]);
  }
  if (!d.mobiles.empty()) addPhysics(d, sim);
}

namespace {

void writeWorldAttributes(pugi::xml_node world, const Simulation& sim, const WorldDescription& original) {
  const GridSize g = sim.world().size();
  world.append_attribute("gridSize") =
      (std::to_string(g.x) + "," + std::to_string(g.y) + "," + std::to_string(g.z)).c_str();
  // The target that actually ran, whatever the original said (it may have come from the command line).
  world.append_attribute("target") = sim.target().name.c_str();
  if (original.seed) world.append_attribute("seed") = std::to_string(*original.seed).c_str();
  // Absolute: the exported file may be written anywhere, and relative paths were resolved at load.
  if (!original.code.empty())
    world.append_attribute("code") = std::filesystem::absolute(original.code).lexically_normal().c_str();
  if (!original.program.empty())
    world.append_attribute("program") =
        std::filesystem::absolute(original.program).lexically_normal().c_str();
}

// The shortest text that reads back as the same double ("50", "0.02", "74.97377511962831").
std::string realText(double v) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : std::to_string(v);
}

void writeKept(pugi::xml_node world, const char* name, const KeptElement& kept) {
  if (!kept.present) return;
  pugi::xml_node n = world.append_child(name);
  for (const auto& [key, value] : kept.attributes) n.append_attribute(key.c_str()) = value.c_str();
}

}  // namespace

void exportWorldXml(const Simulation& sim, const WorldDescription& original, std::ostream& out) {
  pugi::xml_document doc;
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  std::string note =
      " configuration at t = " + formatTime(sim.now()) + ", exported from " + original.path + " ";
  for (std::size_t i; (i = note.find("--")) != std::string::npos;)
    note.replace(i, 2, "- -");  // invalid in comments
  doc.append_child(pugi::node_comment).set_value(note.c_str());
  pugi::xml_node world = doc.append_child("world");
  writeWorldAttributes(world, sim, original);
  writeKept(world, "camera", original.camera);
  writeKept(world, "spotlight", original.spotlight);
  pugi::xml_node list = world.append_child("blockList");
  if (original.listColor) list.append_attribute("color") = colorText(*original.listColor).c_str();
  if (!original.blockSize.empty()) list.append_attribute("blockSize") = original.blockSize.c_str();
  // Every block carries its own color: colors change during a run.
  for (BlockId id = 0; id < sim.world().blockCount(); ++id) {
    if (!sim.world().isAlive(id)) continue;
    const Block& b = sim.world().block(id);
    pugi::xml_node n = list.append_child("block");
    n.append_attribute("position") = cellText(b.cell).c_str();
    n.append_attribute("color") = colorText(b.color).c_str();
    // Block ids of the run are those of the description while no block was added during it.
    if (id < original.blocks.size())
      for (const auto& [key, value] : original.blocks[id].kept)
        n.append_attribute(key.c_str()) = value.c_str();
  }
  if (const Physics* physics = sim.physics()) {  // the mobiles where they are now
    pugi::xml_node mobiles = world.append_child("mobileList");
    for (std::size_t i = 0; i < physics->mobileCount(); ++i) {
      const MobileSpec& m = physics->spec(i);
      const Eigen::Vector2d p = physics->positionMm(i);
      pugi::xml_node n = mobiles.append_child("mobile");
      n.append_attribute("position") = (realText(p.x()) + "," + realText(p.y())).c_str();
      n.append_attribute("size") = (realText(m.lxMm) + "," + realText(m.lyMm)).c_str();
      n.append_attribute("mass") = realText(m.massKg).c_str();
      n.append_attribute("angle") = realText(physics->angleDeg(i)).c_str();
    }
    if (!physics->obstacles().empty()) {
      pugi::xml_node obstacles = world.append_child("obstacleList");
      for (const ObstacleSpec& o : physics->obstacles()) {
        pugi::xml_node n = obstacles.append_child("obstacle");
        n.append_attribute("position") = (realText(o.xMm) + "," + realText(o.yMm)).c_str();
        n.append_attribute("size") = (realText(o.lxMm) + "," + realText(o.lyMm)).c_str();
      }
    }
  }
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  out << '\n';  // pugixml ends the file without one
}

}  // namespace simcore
