#include "simcore/stability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "simcore/simulation.hpp"
#include "simcore/time.hpp"

namespace simcore {

namespace {

constexpr double kGravity = 9.81;   // m/s^2
constexpr double kEpsMm = 1e-6;     // geometric tolerance: on the hull's edge counts as inside

struct Point2 {
  double x, y;
};

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain; collinear points dropped. One point, two (a segment) or a polygon in
// counter-clockwise order.
std::vector<Point2> convexHull(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](const Point2& a, const Point2& b) {
            return std::fabs(a.x - b.x) < kEpsMm && std::fabs(a.y - b.y) < kEpsMm;
          }),
          p.end());
  if (p.size() < 3) return p;
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= kEpsMm * kEpsMm) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= kEpsMm * kEpsMm) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The point of segment [a, b] nearest to p, and its parameter t in [0, 1].
Point2 nearestOnSegment(const Point2& a, const Point2& b, const Point2& p, double& t) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return Point2{a.x + t * dx, a.y + t * dy};
}

bool insideHull(const std::vector<Point2>& h, const Point2& p) {
  if (h.size() < 3) return false;  // a point or a segment: only its boundary, tested by distance
  for (std::size_t i = 0; i < h.size(); ++i)
    if (cross(h[i], h[(i + 1) % h.size()], p) < -kEpsMm * kEpsMm) return false;
  return true;
}

// The pivot of a structure whose centre of mass `g` is off its hull: the hull's nearest edge, or
// its nearest corner (from == to). Returns false when g is over the hull (no pivot: it stands).
bool tippingAxis(const std::vector<Point2>& h, const Point2& g, Point2& from, Point2& to) {
  if (insideHull(h, g)) return false;
  double best = INFINITY;
  const std::size_t edges = h.size() == 1 ? 1 : h.size() == 2 ? 1 : h.size();
  for (std::size_t i = 0; i < edges; ++i) {
    const Point2 &a = h[i], &b = h[(i + 1) % h.size()];
    double t;
    const Point2 q = nearestOnSegment(a, b, g, t);
    const double d = std::hypot(q.x - g.x, q.y - g.y);
    if (d >= best - kEpsMm) continue;
    best = d;
    if (t <= 0 || t >= 1 || h.size() == 1) {
      from = to = t >= 1 ? b : a;
    } else {
      from = a;
      to = b;
    }
  }
  return best > kEpsMm;
}

std::uint64_t cellKey(const Cell& c) {
  auto part = [](std::int32_t v) { return std::uint64_t(std::uint32_t(v + (1 << 20)) & 0x1FFFFF); };
  return part(c.x) | part(c.y) << 21 | part(c.z) << 42;
}

// The configuration as the checker sees it: alive blocks (dense indexes), their cells and centres
// in millimetres, and their links.
struct Layout {
  std::vector<BlockId> ids;
  std::vector<Cell> cells;
  std::vector<Vec3> centres;
  struct Link {
    std::uint32_t other;
    int face;
  };
  std::vector<std::vector<Link>> links;
};

Layout layoutOf(const World& world, const TargetSpec& target, const MovedBlock* moved) {
  Layout l;
  const Lattice& lattice = world.lattice();
  std::unordered_map<std::uint64_t, std::uint32_t> at;
  for (BlockId id = 0; id < world.blockCount(); ++id) {
    if (!world.isAlive(id)) continue;
    const Cell c = moved && moved->id == id ? moved->to : world.block(id).cell;
    at.emplace(cellKey(c), std::uint32_t(l.ids.size()));
    l.ids.push_back(id);
    l.cells.push_back(c);
    const Vec3 p = lattice.cellCenter(c);
    l.centres.push_back(Vec3{p.x * target.blockSizeMm, p.y * target.blockSizeMm, p.z * target.blockSizeMm});
  }
  l.links.resize(l.ids.size());
  for (std::uint32_t i = 0; i < l.ids.size(); ++i)
    for (int f = 0; f < world.faceCount(); ++f)
      if (auto it = at.find(cellKey(lattice.neighborCell(l.cells[i], f))); it != at.end())
        l.links[i].push_back({it->second, f});
  return l;
}

// What rests on the floor touches it here: a cube's bottom corners, a sphere's lowest point.
void floorContacts(const Vec3& c, const TargetSpec& t, std::vector<Point2>& out) {
  if (!t.gravity.flatBottom) {
    out.push_back({c.x, c.y});
    return;
  }
  const double h = t.blockSizeMm / 2;
  for (const double dx : {-h, h})
    for (const double dy : {-h, h}) out.push_back({c.x + dx, c.y + dy});
}

class Checker {
 public:
  Checker(const Layout& l, const TargetSpec& t, StabilityReport& r) : l_(l), t_(t), r_(r), rank_(l.ids.size(), -1) {}

  void structure(const std::vector<std::uint32_t>& members) {
    std::vector<std::uint32_t> floor;
    Vec3 sum{};
    for (std::uint32_t i : members) {
      if (l_.cells[i].z == 0) floor.push_back(i);
      sum = Vec3{sum.x + l_.centres[i].x, sum.y + l_.centres[i].y, sum.z + l_.centres[i].z};
    }
    const double n = double(members.size());
    const Vec3 g{sum.x / n, sum.y / n, sum.z / n};
    if (floor.empty()) {
      r_.falling.push_back({idsOf(members)});
      return;
    }
    balance(floor, members, g);
    loads(floor);
  }

 private:
  std::vector<BlockId> idsOf(const std::vector<std::uint32_t>& members) const {
    std::vector<BlockId> out;
    for (std::uint32_t i : members) out.push_back(l_.ids[i]);
    std::sort(out.begin(), out.end());
    return out;
  }

  void balance(const std::vector<std::uint32_t>& floor, const std::vector<std::uint32_t>& members, const Vec3& g) {
    std::vector<Point2> contacts;
    for (std::uint32_t i : floor) floorContacts(l_.centres[i], t_, contacts);
    Point2 a{}, b{};
    if (!tippingAxis(convexHull(contacts), Point2{g.x, g.y}, a, b)) return;
    TippingStructure tip{idsOf(members), g, Vec3{a.x, a.y, 0}, Vec3{b.x, b.y, 0}, {}};
    for (std::uint32_t i : floor) {
      std::vector<Point2> mine;
      floorContacts(l_.centres[i], t_, mine);
      const bool onAxis = std::any_of(mine.begin(), mine.end(), [&](const Point2& p) {
        double t;
        const Point2 q = nearestOnSegment(a, b, p, t);
        return std::hypot(q.x - p.x, q.y - p.y) < kEpsMm;
      });
      if (onAxis) tip.pivotBlocks.push_back(l_.ids[i]);
    }
    std::sort(tip.pivotBlocks.begin(), tip.pivotBlocks.end());
    r_.tipping.push_back(std::move(tip));
  }

  // Ranks from the floor (breadth first), then the loads from the top down, each block's load
  // shared equally by its carriers (its neighbors one rank lower).
  void loads(const std::vector<std::uint32_t>& floor) {
    std::vector<std::uint32_t> order(floor);
    for (std::uint32_t i : floor) rank_[i] = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
      for (const Layout::Link& link : l_.links[order[k]])
        if (rank_[link.other] < 0) {
          rank_[link.other] = rank_[order[k]] + 1;
          order.push_back(link.other);
        }
    std::vector<double> weight(l_.ids.size(), 0);
    std::vector<Vec3> moment(l_.ids.size());  // sum of the centres of what hangs from a block, itself included
    for (std::uint32_t i : order) {
      weight[i] = 1;
      moment[i] = l_.centres[i];
    }
    for (std::size_t k = order.size(); k-- > floor.size();) {
      const std::uint32_t i = order[k];
      std::size_t carriers = 0;
      for (const Layout::Link& link : l_.links[i]) carriers += rank_[link.other] == rank_[i] - 1;
      const double share = 1.0 / double(carriers);
      const double w = weight[i] * share;
      const Vec3 m{moment[i].x * share, moment[i].y * share, moment[i].z * share};
      for (const Layout::Link& link : l_.links[i]) {
        const std::uint32_t c = link.other;
        if (rank_[c] != rank_[i] - 1) continue;
        linkLoad(c, backFace(c, i), i, w, m);
        weight[c] += w;
        moment[c] = Vec3{moment[c].x + m.x, moment[c].y + m.y, moment[c].z + m.z};
      }
    }
  }

  // The face of `carrier` that touches `held`.
  int backFace(std::uint32_t carrier, std::uint32_t held) const {
    for (const Layout::Link& back : l_.links[carrier])
      if (back.other == held) return back.face;
    throw std::logic_error("stability: a link without its way back");
  }

  void linkLoad(std::uint32_t carrier, int face, std::uint32_t held, double blocks, const Vec3& sum) {
    const Vec3 &p = l_.centres[carrier], &q = l_.centres[held];
    const double len = std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) + (q.z - p.z) * (q.z - p.z));
    const double nz = (q.z - p.z) / len;
    const Vec3 contact{(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2};
    const Vec3 g{sum.x / blocks, sum.y / blocks, sum.z / blocks};
    const double r = std::hypot(g.x - contact.x, g.y - contact.y);
    const double a = t_.gravity.linkLeverMm;
    const double w = blocks * t_.gravity.blockMassKg * kGravity;
    const double momentPart = nz > kEpsMm ? std::max(0.0, r - a / 2) / a : r / a;
    const double f = w * (std::max(0.0, -nz) + std::sqrt(std::max(0.0, 1 - nz * nz)) + momentPart);
    ++r_.loadedLinks;
    r_.maxLinkForceN = std::max(r_.maxLinkForceN, f);
    if (f > t_.gravity.linkStrengthN * (1 + 1e-9))
      r_.overloaded.push_back({l_.ids[carrier], l_.ids[held], face, f, blocks});
  }

  const Layout& l_;
  const TargetSpec& t_;
  StabilityReport& r_;
  std::vector<int> rank_;
};

std::string blockList(const std::vector<BlockId>& ids) {
  constexpr std::size_t kShown = 12;
  std::string s;
  for (std::size_t i = 0; i < ids.size() && i < kShown; ++i) s += (i ? " #" : "#") + std::to_string(ids[i]);
  if (ids.size() > kShown) s += " and " + std::to_string(ids.size() - kShown) + " more";
  return s;
}

// "3 blocks' weight", "1 block's weight", "0.75 of a block's weight".
std::string weightOf(double blocks) {
  std::ostringstream o;
  if (std::fabs(blocks - std::round(blocks)) < 1e-6) {
    const long n = std::lround(blocks);
    o << n << (n == 1 ? " block's weight" : " blocks' weight");
  } else {
    o << std::setprecision(3) << blocks << (blocks < 1 ? " of a block's weight" : " blocks' weight");
  }
  return o.str();
}

std::string mm(const Vec3& v, bool withZ) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << '(' << v.x << ", " << v.y;
  if (withZ) o << ", " << v.z;
  o << ')';
  return o.str();
}

}  // namespace

StabilityReport checkStability(const World& world, const TargetSpec& target, const MovedBlock* moved) {
  if (!target.gravity.applies)
    throw std::invalid_argument(target.name + " blocks do not stand under gravity: nothing to check");
  const Layout l = layoutOf(world, target, moved);
  StabilityReport r;
  r.blocks = l.ids.size();
  r.linkStrengthN = target.gravity.linkStrengthN;
  Checker checker(l, target, r);
  std::vector<char> seen(l.ids.size(), 0);
  for (std::uint32_t start = 0; start < l.ids.size(); ++start) {
    if (seen[start]) continue;
    std::vector<std::uint32_t> members{start};
    seen[start] = 1;
    for (std::size_t k = 0; k < members.size(); ++k)
      for (const Layout::Link& link : l.links[members[k]])
        if (!seen[link.other]) {
          seen[link.other] = 1;
          members.push_back(link.other);
        }
    ++r.structures;
    checker.structure(members);
  }
  return r;
}

void printStability(std::ostream& out, const StabilityReport& r, const TargetSpec& target) {
  std::ostringstream forces;
  forces << std::fixed << std::setprecision(2) << "largest link force " << r.maxLinkForceN << " N of "
         << r.linkStrengthN << " N";
  const auto plural = [](std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  if (r.stable()) {
    out << "stability: stable (" << plural(r.structures, "structure", "structures") << " of "
        << plural(r.blocks, "block", "blocks") << ", " << plural(r.loadedLinks, "loaded link", "loaded links")
        << "; " << forces.str() << ")\n";
    return;
  }
  std::vector<std::string> what;
  if (!r.falling.empty()) what.push_back(plural(r.falling.size(), "structure falls", "structures fall"));
  if (!r.tipping.empty()) what.push_back(plural(r.tipping.size(), "structure tips over", "structures tip over"));
  if (!r.overloaded.empty()) what.push_back(plural(r.overloaded.size(), "link overloaded", "links overloaded"));
  out << "stability: unstable (";
  for (std::size_t i = 0; i < what.size(); ++i) out << (i ? ", " : "") << what[i];
  out << "; " << forces.str() << ")\n";
  for (const FallingStructure& s : r.falling)
    out << "  structure " << blockList(s.blocks) << ": no block on the floor, it falls\n";
  for (const TippingStructure& s : r.tipping) {
    out << "  structure " << blockList(s.blocks) << ": centre of mass " << mm(s.centreOfMassMm, true)
        << " mm outside its floor contacts; it tips about ";
    if (std::hypot(s.pivotFromMm.x - s.pivotToMm.x, s.pivotFromMm.y - s.pivotToMm.y) < kEpsMm)
      out << "the corner " << mm(s.pivotFromMm, false);
    else
      out << "the axis " << mm(s.pivotFromMm, false) << " - " << mm(s.pivotToMm, false);
    out << " mm of floor block" << (s.pivotBlocks.size() == 1 ? " " : "s ") << blockList(s.pivotBlocks) << '\n';
  }
  for (const OverloadedLink& o : r.overloaded) {
    std::ostringstream line;  // (the caller's stream keeps its own number format)
    line << std::fixed << std::setprecision(2) << "  link #" << o.carrier << ' '
         << target.faceNames[std::size_t(o.face)] << " -> #" << o.held << ": must carry " << o.forceN
         << " N, holds " << r.linkStrengthN << " N (" << weightOf(o.hanging) << " on it)\n";
    out << line.str();
  }
}

int StabilityGuard::check(const Simulation& sim, BlockId id, const Cell& to) {
  ++checked_;
  const MovedBlock moved{id, to};
  const StabilityReport r = checkStability(sim.world(), sim.target(), &moved);
  if (r.stable()) return VS_OK;
  ++unstable_;
  if (out_) {
    *out_ << "vsim: " << (refuse_ ? "refused" : "warning") << ": at " << formatTime(sim.now()) << " block #" << id
          << " moving to (" << to.x << "," << to.y << "," << to.z << "): ";
    printStability(*out_, r, sim.target());
  }
  return refuse_ ? VS_ERR_UNSTABLE : VS_OK;
}

}  // namespace simcore
