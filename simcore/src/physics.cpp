#include "simcore/physics.hpp"

#include <algorithm>
#include <cmath>

namespace simcore {

namespace {

constexpr double kMm = 0.001;
constexpr double kStillSpeed = 1e-5;     // m/s: 0.01 mm/s, below which a mobile has stopped
constexpr double kStillSpin = 1e-4;      // rad/s
constexpr double kSpentJet = 1e-4;       // effective power below which a closed jet is gone

Eigen::Matrix2d rotation(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

Physics::Physics(std::vector<Eigen::Vector2d> blockCentresMm, std::vector<MobileSpec> mobiles,
                 std::vector<ObstacleSpec> obstacles, AirJetModel model)
    : mobiles_(std::move(mobiles)), obstacles_(std::move(obstacles)), model_(model), over_(blockCentresMm.size(), -1) {
  blocks_.reserve(blockCentresMm.size());
  for (const Eigen::Vector2d& c : blockCentresMm) blocks_.push_back(c * kMm);
  for (const MobileSpec& m : mobiles_) {
    MobileState s;
    s.position = Eigen::Vector2d(m.xMm, m.yMm) * kMm;
    s.angle = m.angleDeg * M_PI / 180.0;
    state_.push_back(s);
  }
  updateCoverage();  // the first arrivals: the kernel tells those blocks at the start
}

double Physics::angleDeg(std::size_t i) const { return state_[i].angle * 180.0 / M_PI; }

Eigen::Vector2d Physics::corner(std::size_t i, int k) const {
  const double hx = mobiles_[i].lxMm * kMm / 2, hy = mobiles_[i].lyMm * kMm / 2;
  const Eigen::Vector2d local((k == 1 || k == 2) ? hx : -hx, k >= 2 ? hy : -hy);
  return state_[i].position + rotation(state_[i].angle) * local;
}

bool Physics::covers(std::size_t i, const Eigen::Vector2d& p) const {
  const Eigen::Vector2d local = rotation(-state_[i].angle) * (p - state_[i].position);
  return std::fabs(local.x()) <= mobiles_[i].lxMm * kMm / 2 && std::fabs(local.y()) <= mobiles_[i].lyMm * kMm / 2;
}

Eigen::Vector2d Physics::nearestOnFootprint(std::size_t i, const Eigen::Vector2d& p) const {
  const double hx = mobiles_[i].lxMm * kMm / 2, hy = mobiles_[i].lyMm * kMm / 2;
  Eigen::Vector2d local = rotation(-state_[i].angle) * (p - state_[i].position);
  local.x() = std::clamp(local.x(), -hx, hx);
  local.y() = std::clamp(local.y(), -hy, hy);
  return state_[i].position + rotation(state_[i].angle) * local;
}

// Separating axes: the obstacle's two and the mobile's two.
bool Physics::overlapsObstacle(std::size_t i) const {
  Eigen::Vector2d corners[4];
  for (int k = 0; k < 4; ++k) corners[k] = corner(i, k);
  const Eigen::Matrix2d r = rotation(state_[i].angle);
  for (const ObstacleSpec& o : obstacles_) {
    const Eigen::Vector2d c(o.xMm * kMm, o.yMm * kMm), h(o.lxMm * kMm / 2, o.lyMm * kMm / 2);
    const Eigen::Vector2d oc[4] = {c + Eigen::Vector2d(-h.x(), -h.y()), c + Eigen::Vector2d(h.x(), -h.y()),
                                   c + Eigen::Vector2d(h.x(), h.y()), c + Eigen::Vector2d(-h.x(), h.y())};
    const Eigen::Vector2d axes[4] = {{1, 0}, {0, 1}, r.col(0), r.col(1)};
    bool separated = false;
    for (const Eigen::Vector2d& a : axes) {
      double minM = INFINITY, maxM = -INFINITY, minO = INFINITY, maxO = -INFINITY;
      for (int k = 0; k < 4; ++k) {
        minM = std::min(minM, a.dot(corners[k]));
        maxM = std::max(maxM, a.dot(corners[k]));
        minO = std::min(minO, a.dot(oc[k]));
        maxO = std::max(maxO, a.dot(oc[k]));
      }
      if (maxM <= minO || maxO <= minM) {
        separated = true;
        break;
      }
    }
    if (!separated) return true;
  }
  return false;
}

void Physics::setJet(std::uint32_t block, int face, const Eigen::Vector2d& direction, double power, SimTime until) {
  power = std::clamp(power, 0.0, 1.0);
  for (Jet& j : jets_)
    if (j.block == block && j.face == face) {
      j.command = power;
      j.until = until;
      return;
    }
  jets_.push_back(Jet{block, face, direction.normalized(), power, 0.0, until});
}

bool Physics::active() const {
  if (!jets_.empty()) return true;
  for (const MobileState& s : state_)
    if (s.velocity.norm() > kStillSpeed || std::fabs(s.angularVelocity) > kStillSpin) return true;
  return false;
}

bool Physics::step(SimTime now) {
  const double h = double(model_.step) / double(kSecond);
  // The valves: commands end at their time, the effective power follows with the valve's lag.
  for (Jet& j : jets_) {
    if (now >= j.until) j.command = 0;
    j.effective += (j.command - j.effective) * std::min(1.0, h / model_.riseTimeS);
  }
  jets_.erase(std::remove_if(jets_.begin(), jets_.end(),
                             [](const Jet& j) { return j.command == 0 && j.effective < kSpentJet; }),
              jets_.end());
  const double reach = model_.reachMm * kMm;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    MobileState& s = state_[i];
    Eigen::Vector2d force = -model_.dampingNsPerM * s.velocity;
    double torque = -model_.angularDampingNms * s.angularVelocity;
    for (const Jet& j : jets_) {
      const Eigen::Vector2d at = blocks_[j.block];
      const Eigen::Vector2d q = nearestOnFootprint(i, at);
      const double r = (q - at).norm();
      if (r >= reach) continue;
      const Eigen::Vector2d f = model_.maxForceN * j.effective * (1.0 - r / reach) * j.direction;
      force += f;
      torque += cross(q - s.position, f);
    }
    const MobileSpec& m = mobiles_[i];
    const double lx = m.lxMm * kMm, ly = m.lyMm * kMm;
    const double inertia = m.massKg * (lx * lx + ly * ly) / 12.0;
    const MobileState before = s;
    s.position += h * s.velocity;
    s.angle += h * s.angularVelocity;
    s.velocity += h * force / m.massKg;
    s.angularVelocity += h * torque / inertia;
    if (!obstacles_.empty() && overlapsObstacle(i)) {
      s = before;
      s.velocity.setZero();
      s.angularVelocity = 0;
    }
  }
  updateCoverage();
  const bool goOn = active();
  if (!goOn)
    for (MobileState& s : state_) {  // at rest: the next push starts from exactly zero
      s.velocity.setZero();
      s.angularVelocity = 0;
    }
  return goOn;
}

void Physics::updateCoverage() {
  changes_.clear();
  for (std::uint32_t b = 0; b < blocks_.size(); ++b) {
    int now = -1;
    for (std::size_t i = 0; i < state_.size() && now < 0; ++i)
      if (covers(i, blocks_[b])) now = int(i);
    if (now == over_[b]) continue;
    if (over_[b] >= 0) changes_.push_back({b, over_[b], false});
    if (now >= 0) changes_.push_back({b, now, true});
    over_[b] = now;
  }
}

int Physics::mobileOver(std::uint32_t block) const { return block < over_.size() ? over_[block] : -1; }

}  // namespace simcore
