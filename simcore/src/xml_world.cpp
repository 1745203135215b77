// Reading XML world files (format: docs/world-format.md). The loader parses the whole file
// with pugixml in place, so every element and attribute name still points into our own buffer:
// that pointer gives the byte offset, and the offset gives the line:col of every message.
#include "simcore/xml_world.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <pugixml.hpp>
#include <sstream>
#include <unordered_map>

#include "simcore/csg.hpp"

namespace simcore {

XmlWorldError::XmlWorldError(std::string file, int line, int column, std::string message)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                                        ": error: " + message
                                  : file + ": error: " + message),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(std::move(message)) {}

namespace {

constexpr std::uint64_t kMaxCells = std::uint64_t(1) << 31;

// Byte offsets -> line:column. Columns count characters (UTF-8 lead bytes), as editors do.
class SourceMap {
 public:
  explicit SourceMap(std::string_view text) : text_(text) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') lineStarts_.push_back(i + 1);
  }
  SourcePos at(std::size_t offset) const {
    offset = std::min(offset, text_.size());
    std::size_t line =
        std::size_t(std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset) - lineStarts_.begin());
    int column = 1;
    for (std::size_t i = lineStarts_[line - 1]; i < offset; ++i)
      if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) ++column;
    return SourcePos{int(line), column};
  }

 private:
  std::string_view text_;
  std::vector<std::size_t> lineStarts_;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// "1, 2,3" -> {1,2,3}; nullopt if any component is not a whole integer.
std::optional<std::vector<long long>> parseIntList(std::string_view text) {
  std::vector<long long> values;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view part = trim(text.substr(0, comma));
    long long v = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size()) return std::nullopt;
    values.push_back(v);
    if (comma == std::string_view::npos) return values;
    text.remove_prefix(comma + 1);
  }
}

bool sameName(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

bool inNames(std::string_view name, std::initializer_list<std::string_view> names) {
  return std::any_of(names.begin(), names.end(), [&](std::string_view n) { return sameName(name, n); });
}

// Colors: "r,g,b" with components in 0..255 (fractions allowed, rounded: VisibleSim reads them as
// reals), "#RRGGBB" or "0xRRGGBB". nullopt if malformed or out of range.
std::optional<std::uint32_t> parseColor(std::string_view text) {
  text = trim(text);
  std::string_view hex;
  if (text.starts_with('#'))
    hex = text.substr(1);
  else if (text.starts_with("0x") || text.starts_with("0X"))
    hex = text.substr(2);
  if (!hex.empty() || text == "#") {
    std::uint32_t rgb = 0;
    const auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), rgb, 16);
    if (hex.size() != 6 || ec != std::errc() || end != hex.data() + hex.size()) return std::nullopt;
    return rgb;
  }
  const auto v = parseRealList(text);
  if (!v || v->size() < 3 || v->size() > 4) return std::nullopt;  // a 4th component: alpha, ignored
  std::uint32_t rgb = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double c = (*v)[i];
    if (c < 0 || c > 255) return std::nullopt;
    rgb = (rgb << 8) | std::uint32_t(std::lround(c));
  }
  return rgb;
}

std::string cellText(const Cell& c) {
  // Appended piece by piece: "(" + std::string&& trips a false -Wrestrict in GCC 12.
  std::string s = "(";
  s += std::to_string(c.x);
  s += ',';
  s += std::to_string(c.y);
  s += ',';
  s += std::to_string(c.z);
  s += ')';
  return s;
}

class Loader {
 public:
  Loader(std::string_view text, std::string path) : map_(text), buffer_(text), path_(std::move(path)) {
    world_.path = path_;
  }
  WorldDescription run();

 private:
  using Attr = pugi::xml_attribute;
  using Node = pugi::xml_node;

  // --- Positions and messages ---
  SourcePos posOfPointer(const char* p) const {
    if (p < buffer_.data() || p > buffer_.data() + buffer_.size()) return SourcePos{1, 1};
    return map_.at(std::size_t(p - buffer_.data()));
  }
  // The '<' of the start tag (pugixml's name pointer is just after it).
  SourcePos posOf(Node n) const { return posOfPointer(n.name() - 1); }
  SourcePos posOf(Attr a) const { return posOfPointer(a.name()); }
  [[noreturn]] void fail(SourcePos p, const std::string& message) const {
    throw XmlWorldError(path_, p.line, p.column, message);
  }
  [[noreturn]] void badAttribute(Node n, Attr a, const std::string& problem) const {
    fail(posOf(a),
         "attribute '" + std::string(a.name()) + "' of <" + n.name() + ">: \"" + a.value() + "\" " + problem);
  }
  void warn(SourcePos p, const std::string& message) {
    world_.warnings.push_back(path_ + ":" + std::to_string(p.line) + ":" + std::to_string(p.column) +
                              ": warning: " + message);
  }
  void warnUnknownAttributes(Node n, std::initializer_list<std::string_view> known);
  // Attribute and element names are matched without regard to case (VisibleSim's own files write
  // gridsize, gridSize and GridSize alike).
  static Attr attr(Node n, std::string_view name) {
    for (Attr a : n.attributes())
      if (sameName(a.name(), name)) return a;
    return Attr();
  }
  Attr required(Node n, const char* name) const {
    Attr a = attr(n, name);
    if (!a) fail(posOf(n), "<" + std::string(n.name()) + "> needs attribute '" + name + "'");
    return a;
  }

  // --- Values ---
  Cell cellAttribute(Node n, Attr a) const;
  std::uint32_t colorAttribute(Node n, Attr a) const;
  std::optional<std::uint32_t> optionalColor(Node n, std::optional<std::uint32_t> fallback) const {
    Attr a = attr(n, "color");
    return a ? std::optional<std::uint32_t>(colorAttribute(n, a)) : fallback;
  }
  Cell checkedCell(Node n, Attr a) const;
  Cell sizeAttribute(Node n, Attr a) const;
  long long positiveInt(Node n, Attr a) const;

  // --- Elements ---
  void readWorld(Node world);
  void readWorldAttributes(Node world);
  void readGridSize(Node world, Attr a);
  void readKept(Node n, KeptElement& into);
  void readBlockList(Node list);
  void readBlock(Node n, std::optional<std::uint32_t> listColor);
  void readBox(Node n, std::optional<std::uint32_t> listColor);
  void readLine(Node n, std::optional<std::uint32_t> listColor);
  void readVisibleSimBox(Node n, std::optional<std::uint32_t> listColor);
  void readBitmapLine(Node n, std::optional<std::uint32_t> listColor);
  void readCsg(Node n, std::optional<std::uint32_t> listColor);
  bool boolAttribute(Node n, const char* name, bool fallback) const;
  void fillBox(Node n, Attr sizeAttr, const Cell& origin, const Cell& size,
               std::optional<std::uint32_t> color);
  void readSchedule(Node schedule);
  void readMobiles(Node list);
  void readObstacles(Node list);
  // A list of `count` finite numbers (positive ones when `positive`), or a message at the attribute.
  std::vector<double> numbers(Node n, Attr a, std::size_t count, bool positive) const;
  BlockId blockIdAttribute(Node n);
  SimTime timeAttribute(Node n);
  void checkScheduledBlocks();
  void addBlock(Node n, Attr where, const Cell& c, std::optional<std::uint32_t> color);
  // Calls `f(child)` for element children; warns about text and about elements not in `known`.
  template <class F>
  void forChildren(Node parent, std::initializer_list<std::string_view> known, F f);

  SourceMap map_;
  std::string buffer_;  // parsed in place, so names and values point into it
  std::string path_;
  WorldDescription world_;
  std::unordered_map<std::uint64_t, std::size_t> occupied_;     // cell index -> block index
  std::vector<std::pair<BlockId, SourcePos>> scheduledBlocks_;  // block attribute of each tap/accel
  bool sawBlockList_ = false;
};

void Loader::warnUnknownAttributes(Node n, std::initializer_list<std::string_view> known) {
  for (Attr a : n.attributes())
    if (!inNames(a.name(), known))
      warn(posOf(a), "unknown attribute '" + std::string(a.name()) + "' of <" + n.name() + "> ignored");
}

template <class F>
void Loader::forChildren(Node parent, std::initializer_list<std::string_view> known, F f) {
  for (Node child : parent.children()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      const std::string_view text = child.value();
      const std::size_t first = text.find_first_not_of(" \t\r\n");
      if (first != std::string_view::npos)
        warn(posOfPointer(text.data() + first), "text inside <" + std::string(parent.name()) + "> ignored");
      continue;
    }
    if (child.type() != pugi::node_element) continue;
    if (!inNames(child.name(), known)) {
      warn(posOf(child), "unknown element <" + std::string(child.name()) + "> ignored");
      continue;
    }
    f(child);
  }
}

Cell Loader::cellAttribute(Node n, Attr a) const {
  // Two components are the planar (Smart Blocks) form of VisibleSim: z = 0.
  const auto v = parseIntList(a.value());
  if (!v || v->size() < 2 || v->size() > 3) badAttribute(n, a, "is not three integers");
  for (long long c : *v)
    if (c < INT32_MIN || c > INT32_MAX) badAttribute(n, a, "is not three integers");
  return Cell{std::int32_t((*v)[0]), std::int32_t((*v)[1]), v->size() == 3 ? std::int32_t((*v)[2]) : 0};
}

Cell Loader::sizeAttribute(Node n, Attr a) const {
  // A planar size (two components) is one layer deep.
  Cell size = cellAttribute(n, a);
  if (std::count(a.value(), a.value() + std::strlen(a.value()), ',') == 1) size.z = 1;
  return size;
}

Cell Loader::checkedCell(Node n, Attr a) const {
  const Cell c = cellAttribute(n, a);
  const GridSize& g = world_.grid;
  if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= g.x || c.y >= g.y || c.z >= g.z)
    badAttribute(
        n, a,
        "is outside the grid " + std::to_string(g.x) + "x" + std::to_string(g.y) + "x" + std::to_string(g.z));
  return c;
}

std::uint32_t Loader::colorAttribute(Node n, Attr a) const {
  const std::optional<std::uint32_t> rgb = parseColor(a.value());
  if (!rgb) badAttribute(n, a, "is not a color: r,g,b in 0..255, #RRGGBB or 0xRRGGBB");
  return *rgb;
}

long long Loader::positiveInt(Node n, Attr a) const {
  const auto v = parseIntList(a.value());
  if (!v || v->size() != 1 || (*v)[0] <= 0 || (*v)[0] > INT32_MAX)
    badAttribute(n, a, "is not a positive integer");
  return (*v)[0];
}

WorldDescription Loader::run() {
  pugi::xml_document doc;
  const pugi::xml_parse_result r =
      doc.load_buffer_inplace(buffer_.data(), buffer_.size(), pugi::parse_default, pugi::encoding_utf8);
  if (r.status == pugi::status_no_document_element)
    fail(SourcePos{1, 1}, "no root element: expected <world>");
  if (!r)
    fail(map_.at(std::size_t(std::max<std::ptrdiff_t>(r.offset, 0))),
         std::string("malformed XML: ") + r.description());
  Node root = doc.document_element();
  // VisibleSim's newer files wrap <world> in <vs>, beside <visuals>, <vm>, <parameters> ... that
  // describe its own windows and interpreter: those are skipped.
  if (sameName(root.name(), "vs")) {
    Node world;
    for (Node child : root.children())
      if (child.type() == pugi::node_element && sameName(child.name(), "world")) {
        if (world) {
          warn(posOf(child), "second <world> ignored");
          continue;
        }
        world = child;
      }
    if (!world) fail(posOf(root), "<vs> holds no <world>");
    root = world;
  } else if (!sameName(root.name(), "world")) {
    fail(posOf(root), "the root element is <" + std::string(root.name()) + ">, expected <world> or <vs>");
  }
  for (Node extra = root.next_sibling(); extra; extra = extra.next_sibling())
    if (extra.type() == pugi::node_element && !sameName(extra.parent().name(), "vs"))
      warn(posOf(extra), "element <" + std::string(extra.name()) + "> after <world> ignored");
  readWorld(root);
  // A world without blocks is almost always a file whose block elements we did not understand:
  // running it would print an empty summary and exit 0.
  if (world_.blocks.empty() && !world_.csg)
    fail(posOf(root),
         "the world has no block (no <block>, <blocksBox>, <blockBox>, <blocksLine> or <csg> in a "
         "<blockList>)");
  return std::move(world_);
}

void Loader::readWorld(Node world) {
  readWorldAttributes(world);
  forChildren(world, {"camera", "spotlight", "blockList", "schedule", "mobileList", "obstacleList"}, [&](Node child) {
    const std::string_view name = child.name();
    if (sameName(name, "camera"))
      readKept(child, world_.camera);
    else if (sameName(name, "spotlight"))
      readKept(child, world_.spotlight);
    else if (sameName(name, "blockList"))
      readBlockList(child);
    else if (sameName(name, "mobileList"))
      readMobiles(child);
    else if (sameName(name, "obstacleList"))
      readObstacles(child);
    else
      readSchedule(child);
  });
  // Checked last: a <schedule> may come before the blocks it names.
  checkScheduledBlocks();
}

void Loader::readWorldAttributes(Node world) {
  warnUnknownAttributes(world, {"gridSize", "windowSize", "target", "seed", "code", "program"});
  readGridSize(world, required(world, "gridSize"));
  if (Attr t = attr(world, "target")) {
    world_.target = std::string(trim(t.value()));
    world_.targetPos = posOf(t);
  }
  if (Attr a = attr(world, "seed")) {
    const std::string_view v = trim(a.value());
    std::uint64_t seed = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), seed);
    if (v.empty() || ec != std::errc() || end != v.data() + v.size())
      badAttribute(world, a, "is not a non-negative integer");
    world_.seed = seed;
  }
  // Relative paths name files next to the world file, wherever the simulator is started from.
  const auto resolve = [&](const char* p) -> std::string {
    if (!*p || std::filesystem::path(p).is_absolute()) return p;
    return (std::filesystem::path(path_).parent_path() / p).lexically_normal().string();
  };
  world_.codeAsWritten = attr(world, "code").value();
  world_.code = resolve(attr(world, "code").value());
  world_.program = resolve(attr(world, "program").value());
}

void Loader::readGridSize(Node world, Attr a) {
  // Two components: the planar VisibleSim form, one layer high.
  const auto v = parseIntList(a.value());
  if (!v || v->size() < 2 || v->size() > 3) badAttribute(world, a, "is not three positive integers");
  std::uint64_t cells = 1;
  for (long long c : *v) {
    if (c <= 0 || c > INT32_MAX) badAttribute(world, a, "is not three positive integers");
    cells *= std::uint64_t(c);
    if (cells > kMaxCells) badAttribute(world, a, "has more than 2^31 cells");
  }
  world_.grid =
      GridSize{std::int32_t((*v)[0]), std::int32_t((*v)[1]), v->size() == 3 ? std::int32_t((*v)[2]) : 1};
}

void Loader::readKept(Node n, KeptElement& into) {
  if (into.present) {
    warn(posOf(n), "second <" + std::string(n.name()) + "> ignored");
    return;
  }
  const std::initializer_list<std::string_view> kKnown = {"target", "directionSpherical", "angle", "near",
                                                          "far"};
  warnUnknownAttributes(n, kKnown);
  into.present = true;
  for (Attr a : n.attributes())
    if (std::find(kKnown.begin(), kKnown.end(), std::string_view(a.name())) != kKnown.end())
      into.attributes.emplace_back(a.name(), a.value());
}

void Loader::readBlockList(Node list) {
  warnUnknownAttributes(list, {"color", "blockSize", "blocksSize"});
  const std::optional<std::uint32_t> color = optionalColor(list, std::nullopt);
  // Older VisibleSim files spell it blocksSize.
  Attr size = attr(list, "blockSize") ? attr(list, "blockSize") : attr(list, "blocksSize");
  if (size) {
    const auto v = parseRealList(size.value());
    if (!v || v->size() != 3 || (*v)[0] <= 0 || (*v)[1] <= 0 || (*v)[2] <= 0)
      badAttribute(list, size, "is not three positive numbers");
  }
  if (!sawBlockList_) {
    world_.listColor = color;
    world_.blockSize = size.value();
    sawBlockList_ = true;
  }
  forChildren(list, {"block", "blocksBox", "blockBox", "blocksLine", "csg"}, [&](Node child) {
    const std::string_view name = child.name();
    if (sameName(name, "block"))
      readBlock(child, color);
    else if (sameName(name, "blocksBox"))
      readBox(child, color);
    else if (sameName(name, "blockBox"))
      readVisibleSimBox(child, color);
    else if (sameName(name, "blocksLine") && attr(child, "values"))
      readBitmapLine(child, color);
    else if (sameName(name, "blocksLine"))
      readLine(child, color);
    else
      readCsg(child, color);
  });
}

void Loader::addBlock(Node n, Attr where, const Cell& c, std::optional<std::uint32_t> color) {
  const GridSize& g = world_.grid;
  const std::uint64_t key =
      std::uint64_t(c.x) +
      std::uint64_t(g.x) * (std::uint64_t(c.y) + std::uint64_t(g.y) * std::uint64_t(c.z));
  const auto [it, inserted] = occupied_.emplace(key, world_.blocks.size());
  if (!inserted) {
    const BlockDescription& other = world_.blocks[it->second];
    fail(posOf(where), "<" + std::string(n.name()) + ">: cell " + cellText(c) + " already holds block " +
                           std::to_string(it->second) + " (line " + std::to_string(other.pos.line) + ")");
  }
  world_.blocks.push_back(BlockDescription{c, color, posOf(n), {}});
}

void Loader::readBlock(Node n, std::optional<std::uint32_t> listColor) {
  warnUnknownAttributes(n, {"position", "color", "orientation", "rotation"});
  Attr position = required(n, "position");
  addBlock(n, position, checkedCell(n, position), optionalColor(n, listColor));
  // Catoms' orientation (and rotation): kept so that an exported world says it again.
  for (const char* kept : {"orientation", "rotation"})
    if (Attr a = attr(n, kept)) world_.blocks.back().kept.emplace_back(kept, a.value());
}

void Loader::readVisibleSimBox(Node n, std::optional<std::uint32_t> listColor) {
  // VisibleSim's <blockBox boxOrigin="x,y,z" boxSize="sx,sy,sz">: by default from the origin of
  // the grid to its far corner.
  warnUnknownAttributes(n, {"boxOrigin", "boxSize", "color"});
  const GridSize& g = world_.grid;
  Attr originAttr = attr(n, "boxOrigin"), sizeAttr = attr(n, "boxSize");
  const Cell origin = originAttr ? checkedCell(n, originAttr) : Cell{0, 0, 0};
  const Cell size =
      sizeAttr ? sizeAttribute(n, sizeAttr) : Cell{g.x - origin.x, g.y - origin.y, g.z - origin.z};
  // Without boxSize the box ends at the grid's far corner, so only a given size can be wrong.
  fillBox(n, sizeAttr ? sizeAttr : originAttr, origin, size, optionalColor(n, listColor));
}

void Loader::readBitmapLine(Node n, std::optional<std::uint32_t> listColor) {
  // VisibleSim's bitmap rows: <blocksLine line="y" [plane="z"] values="0110..."/>: a block at
  // x = i for every '1' at index i.
  warnUnknownAttributes(n, {"line", "plane", "values", "color"});
  Attr lineAttr = required(n, "line"), values = required(n, "values");
  Attr planeAttr = attr(n, "plane");
  const auto y = parseIntList(lineAttr.value());
  if (!y || y->size() != 1 || (*y)[0] < 0 || (*y)[0] >= world_.grid.y)
    badAttribute(n, lineAttr, "is not a row of the grid (0.." + std::to_string(world_.grid.y - 1) + ")");
  long long z = 0;
  if (planeAttr) {
    const auto p = parseIntList(planeAttr.value());
    if (!p || p->size() != 1 || (*p)[0] < 0 || (*p)[0] >= world_.grid.z)
      badAttribute(n, planeAttr, "is not a plane of the grid (0.." + std::to_string(world_.grid.z - 1) + ")");
    z = (*p)[0];
  }
  const std::string_view bits = trim(values.value());
  const std::optional<std::uint32_t> color = optionalColor(n, listColor);
  for (std::size_t x = 0; x < bits.size(); ++x) {
    if (bits[x] == '0') continue;
    if (bits[x] != '1')
      badAttribute(n, values, "holds '" + std::string(1, bits[x]) + "': only 0 and 1 are allowed");
    if (std::int64_t(x) >= world_.grid.x)
      badAttribute(n, values, "has a block at x = " + std::to_string(x) + ", outside the grid");
    addBlock(n, values, Cell{std::int32_t(x), std::int32_t((*y)[0]), std::int32_t(z)}, color);
  }
}

void Loader::readBox(Node n, std::optional<std::uint32_t> listColor) {
  warnUnknownAttributes(n, {"origin", "size", "color"});
  Attr originAttr = required(n, "origin"), sizeAttr = required(n, "size");
  const Cell origin = checkedCell(n, originAttr);
  const Cell size = sizeAttribute(n, sizeAttr);
  fillBox(n, sizeAttr, origin, size, optionalColor(n, listColor));
}

void Loader::fillBox(Node n, Attr sizeAttr, const Cell& origin, const Cell& size,
                     std::optional<std::uint32_t> color) {
  const GridSize& g = world_.grid;
  if (size.x <= 0 || size.y <= 0 || size.z <= 0) badAttribute(n, sizeAttr, "is not three positive integers");
  if (std::int64_t(origin.x) + size.x > g.x || std::int64_t(origin.y) + size.y > g.y ||
      std::int64_t(origin.z) + size.z > g.z)
    badAttribute(n, sizeAttr, "makes the box from " + cellText(origin) + " leave the grid");
  // x varies fastest, then y, then z: the documented id order of a box.
  for (std::int32_t z = 0; z < size.z; ++z)
    for (std::int32_t y = 0; y < size.y; ++y)
      for (std::int32_t x = 0; x < size.x; ++x)
        addBlock(n, sizeAttr, Cell{origin.x + x, origin.y + y, origin.z + z}, color);
}

void Loader::readLine(Node n, std::optional<std::uint32_t> listColor) {
  warnUnknownAttributes(n, {"origin", "direction", "length", "color"});
  Attr originAttr = required(n, "origin"), dirAttr = required(n, "direction"),
       lenAttr = required(n, "length");
  const Cell origin = checkedCell(n, originAttr);
  std::string_view dir = trim(dirAttr.value());
  const int sign = dir.starts_with('-') ? -1 : 1;
  if (dir.starts_with('-') || dir.starts_with('+')) dir.remove_prefix(1);
  if (dir != "x" && dir != "y" && dir != "z") badAttribute(n, dirAttr, "is not one of x, y, z, -x, -y, -z");
  const Cell step{dir == "x" ? sign : 0, dir == "y" ? sign : 0, dir == "z" ? sign : 0};
  const long long length = positiveInt(n, lenAttr);
  const GridSize& g = world_.grid;
  const std::int64_t ex = origin.x + step.x * (length - 1), ey = origin.y + step.y * (length - 1),
                     ez = origin.z + step.z * (length - 1);
  if (ex < 0 || ey < 0 || ez < 0 || ex >= g.x || ey >= g.y || ez >= g.z)
    badAttribute(n, lenAttr, "makes the line from " + cellText(origin) + " leave the grid");
  const std::optional<std::uint32_t> color = optionalColor(n, listColor);
  for (long long i = 0; i < length; ++i)
    addBlock(n, lenAttr,
             Cell{std::int32_t(origin.x + step.x * i), std::int32_t(origin.y + step.y * i),
                  std::int32_t(origin.z + step.z * i)},
             color);
}

BlockId Loader::blockIdAttribute(Node n) {
  Attr a = required(n, "block");
  const std::string_view v = trim(a.value());
  BlockId id = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), id);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size() || id == kNoBlock)
    badAttribute(n, a, "is not a block id (a non-negative integer)");
  scheduledBlocks_.emplace_back(id, posOf(a));
  return id;
}

SimTime Loader::timeAttribute(Node n) {
  Attr a = required(n, "time");
  const std::optional<SimTime> t = parseDuration(trim(a.value()));
  if (!t) badAttribute(n, a, "is not a duration (like 1.5s, 250ms, 10us, 42ns)");
  return *t;
}

void Loader::readSchedule(Node schedule) {
  warnUnknownAttributes(schedule, {});
  forChildren(schedule, {"tap", "accel"}, [&](Node n) {
    if (std::string_view(n.name()) == "tap") {
      warnUnknownAttributes(n, {"block", "time"});
      const BlockId id = blockIdAttribute(n);
      world_.taps.push_back(ScheduledTap{id, timeAttribute(n), posOf(n)});
      return;
    }
    warnUnknownAttributes(n, {"block", "time", "value"});
    const BlockId id = blockIdAttribute(n);
    const SimTime t = timeAttribute(n);
    Attr value = required(n, "value");
    const auto v = parseIntList(value.value());
    if (!v || v->size() != 3) badAttribute(n, value, "is not three integers");
    for (long long c : *v)
      if (c < INT32_MIN || c > INT32_MAX) badAttribute(n, value, "is not three integers");
    world_.accels.push_back(ScheduledAccel{
        id, t, {std::int32_t((*v)[0]), std::int32_t((*v)[1]), std::int32_t((*v)[2])}, posOf(n)});
  });
}

std::vector<double> Loader::numbers(Node n, Attr a, std::size_t count, bool positive) const {
  const auto v = parseRealList(a.value());
  const char* what = count == 1 ? (positive ? "is not a positive number" : "is not a number")
                                : (positive ? "is not two positive numbers (like 50,50)" : "is not two numbers (like 75,425)");
  if (!v || v->size() != count) badAttribute(n, a, what);
  for (double x : *v)
    if (positive && !(x > 0)) badAttribute(n, a, what);
  return *v;
}

void Loader::readMobiles(Node list) {
  warnUnknownAttributes(list, {});
  forChildren(list, {"mobile"}, [&](Node n) {
    warnUnknownAttributes(n, {"position", "size", "mass", "angle"});
    MobileSpec m;
    const std::vector<double> p = numbers(n, required(n, "position"), 2, false);
    m.xMm = p[0];
    m.yMm = p[1];
    if (Attr a = attr(n, "size")) {
      const std::vector<double> size = numbers(n, a, 2, true);
      m.lxMm = size[0];
      m.lyMm = size[1];
    }
    if (Attr a = attr(n, "mass")) m.massKg = numbers(n, a, 1, true)[0];
    if (Attr a = attr(n, "angle")) m.angleDeg = numbers(n, a, 1, false)[0];
    world_.mobiles.push_back(MobileDescription{m, posOf(n)});
  });
}

void Loader::readObstacles(Node list) {
  warnUnknownAttributes(list, {});
  forChildren(list, {"obstacle"}, [&](Node n) {
    warnUnknownAttributes(n, {"position", "size"});
    ObstacleSpec o;
    const std::vector<double> p = numbers(n, required(n, "position"), 2, false);
    const std::vector<double> size = numbers(n, required(n, "size"), 2, true);
    o.xMm = p[0];
    o.yMm = p[1];
    o.lxMm = size[0];
    o.lyMm = size[1];
    world_.obstacles.push_back(ObstacleDescription{o, posOf(n)});
  });
}

void Loader::readCsg(Node n, std::optional<std::uint32_t> listColor) {
  warnUnknownAttributes(n, {"content", "boundingBox", "offset", "orientation", "color"});
  if (world_.csg) {
    warn(posOf(n), "second <csg> ignored (a world has one solid, as in VisibleSim)");
    return;
  }
  Attr content = required(n, "content");
  try {
    const CsgSolid solid = CsgSolid::parse(content.value());
    for (const std::string& w : solid.warnings()) warn(posOf(content), "<csg>: " + w);
  } catch (const CsgError& e) {
    fail(posOfPointer(content.value() + std::min(e.offset(), std::strlen(content.value()))),
         std::string("<csg content>: ") + e.what());
  }
  world_.csg = CsgDescription{content.value(), boolAttribute(n, "boundingBox", true),
                              boolAttribute(n, "offset", true), optionalColor(n, listColor), posOf(n)};
}

bool Loader::boolAttribute(Node n, const char* name, bool fallback) const {
  Attr a = attr(n, name);
  if (!a) return fallback;
  const std::string_view v = trim(a.value());
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  badAttribute(n, a, "is neither true nor false");
}

void Loader::checkScheduledBlocks() {
  if (world_.csg) return;  // the solid's blocks are only known with the lattice: checked when populating
  const std::size_t count = world_.blocks.size();
  for (const auto& [id, pos] : scheduledBlocks_)
    if (id >= count)
      fail(pos, "block " + std::to_string(id) + " does not exist: the world has " + std::to_string(count) +
                    " blocks" + (count ? " (ids 0.." + std::to_string(count - 1) + ")" : std::string()));
}

}  // namespace

std::optional<std::vector<double>> parseRealList(std::string_view text) {
  std::vector<double> values;
  std::istringstream in{std::string(text)};
  std::string part;
  while (std::getline(in, part, ',')) {
    const std::string p(trim(part));
    char* end = nullptr;
    const double v = std::strtod(p.c_str(), &end);
    if (p.empty() || end != p.c_str() + p.size() || !std::isfinite(v)) return std::nullopt;
    values.push_back(v);
  }
  if (values.empty() || (!text.empty() && text.back() == ',')) return std::nullopt;
  return values;
}

WorldDescription parseWorldXml(std::string_view text, const std::string& pathForMessages) {
  return Loader(text, pathForMessages).run();
}

WorldDescription loadWorldXml(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw XmlWorldError(path, 0, 0, "is a directory, not a world file");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw XmlWorldError(path, 0, 0, "cannot open the world file: " + std::string(std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw XmlWorldError(path, 0, 0, "cannot read the world file");
  return parseWorldXml(text.str(), path);
}

}  // namespace simcore
