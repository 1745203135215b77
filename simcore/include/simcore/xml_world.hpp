// XML world files in the VisibleSim format (Blinky Blocks, Smart Blocks, Catoms 2D and 3D: block
// positions are lattice cells, whatever the lattice) plus our own attributes:
// reading them into a plain description, building a Simulation from one, and writing the final
// configuration of a run back in the same format. The format is documented in
// docs/world-format.md.
//
// The loader knows nothing of targets (simcore must not depend on targets/): the target name is
// stored as written, and the front end turns it into a TargetSpec.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "simcore/lattice.hpp"
#include "simcore/physics_spec.hpp"
#include "simcore/time.hpp"
#include "simcore/world.hpp"

namespace simcore {

class Simulation;

// An error in a world file. what() is "file:line:col: error: message" (or "file: error: message"
// when there is no position, e.g. the file cannot be read); the parts are kept for the IDE.
class XmlWorldError : public std::runtime_error {
 public:
  XmlWorldError(std::string file, int line, int column, std::string message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }      // 1-based; 0 = no position
  int column() const { return column_; }  // 1-based, in characters
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_, column_;
  std::string message_;
};

// Where something was written in the file (1-based; 0 = made by code, not read from a file).
struct SourcePos {
  int line = 0, column = 0;
};

struct BlockDescription {
  Cell cell;
  std::optional<std::uint32_t> color;  // 0xRRGGBB; nullopt = the target's default color
  SourcePos pos;                       // the <block>, <blocksBox> or <blocksLine> that made it
  // Attributes written back as read (Catoms' orientation and rotation).
  std::vector<std::pair<std::string, std::string>> kept;
};

struct ScheduledTap {
  BlockId block = 0;  // dense id: index in WorldDescription::blocks
  SimTime time = 0;
  SourcePos pos;
};

struct ScheduledAccel {
  BlockId block = 0;
  SimTime time = 0;
  std::array<std::int32_t, 3> value{};
  SourcePos pos;
};

// Attributes of an element we keep only to write them back (<camera>, <spotlight>), in file order.
struct KeptElement {
  bool present = false;
  std::vector<std::pair<std::string, std::string>> attributes;
};

// VisibleSim's <csg content="..." boundingBox="true" offset="true"/>: a solid whose inside becomes
// blocks (csg.hpp). Expanded by populateSimulation, which knows the lattice: a cell is a block when
// its VisibleSim position (Lattice::csgPoint), moved by the solid's bounding box corner (and by
// (-1, -1, -1) with offset), is inside; cells already holding a block are left alone.
struct CsgDescription {
  std::string content;
  bool boundingBox = true, offset = true;
  std::optional<std::uint32_t> color;  // of the block list, for the parts outside any color()
  SourcePos pos;                       // of the <csg> element
};

// <mobileList><mobile position="75,425" size="50,50" mass="0.02" angle="0"/></mobileList> and
// <obstacleList><obstacle position="x,y" size="lx,ly"/></obstacleList>: millimetres on the surface
// (x east, y north; block i's centre is at i * block size), kilograms, degrees.
struct MobileDescription {
  MobileSpec spec;
  SourcePos pos;
};
struct ObstacleDescription {
  ObstacleSpec spec;
  SourcePos pos;
};

struct WorldDescription {
  std::string path;     // the file read (or the name given to parseWorldXml)
  std::string target;   // as written, blanks trimmed ("" if absent); not validated here
  SourcePos targetPos;  // of the target attribute, for the front end's message
  GridSize grid;
  std::optional<std::uint32_t> listColor;  // color="..." of the first <blockList>
  std::string blockSize;                   // blockSize="..." of the first <blockList>, validated
  KeptElement camera, spotlight;
  std::vector<BlockDescription> blocks;  // in document order = dense block ids
  std::optional<CsgDescription> csg;     // its blocks come after `blocks`
  std::optional<std::uint64_t> seed;
  std::string code;     // C BlockCode .so; relative paths resolved against the file's folder
  std::string codeAsWritten;  // the attribute itself: a bare file name is searched for (vsim)
  std::string program;  // Meld program; resolved likewise
  std::vector<ScheduledTap> taps;
  std::vector<ScheduledAccel> accels;
  std::vector<MobileDescription> mobiles;
  std::vector<ObstacleDescription> obstacles;
  AirJetModel airJets;  // not in the file: the front end may change it (vsim --physics-step)
  std::vector<std::string> warnings;  // "file:line:col: warning: ..." (unknown elements, ...)
};

// "40, 40, 25.5": the comma-separated numbers world files write (blockSize, camera target ...);
// nullopt unless every item is a finite number.
std::optional<std::vector<double>> parseRealList(std::string_view text);

// Reads and validates a world file. Throws XmlWorldError.
WorldDescription loadWorldXml(const std::string& path);
// The same from text in memory; `pathForMessages` names it in messages and resolves relative paths.
WorldDescription parseWorldXml(std::string_view text, const std::string& pathForMessages);

// Adds the blocks (in order, so ids match the description; then those of the <csg> solid) to a
// simulation that has none yet, and schedules the taps and accelerometer readings. Throws XmlWorldError at
// the offending element (cell outside the simulation's grid, tap on an unknown block, tap on a target without
// tap ...).
void populateSimulation(const WorldDescription& world, Simulation& sim);

// Writes the current configuration (cells and colors of the alive blocks, renumbered densely in id
// order) in the same format, keeping gridSize, camera, spotlight and the <world> attributes of
// `original`. The schedule is not written: it belongs to the run that already happened.
void exportWorldXml(const Simulation& sim, const WorldDescription& original, std::ostream& out);

}  // namespace simcore
