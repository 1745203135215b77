#define BOOST_TEST_MODULE simcore_physics
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "simcore/physics.hpp"
#include "simcore/xml_world.hpp"
#include "test_support.hpp"

// The air-jet physics (simcore/physics.hpp) alone and inside a Simulation of Smart Blocks (25 mm:
// block (i, j) has its centre at (25 i, 25 j) mm; faces north 0, east 1, south 2, west 3).

using namespace simcore;
using testsupport::Script;

namespace {

constexpr int kNorth = 0, kEast = 1;

std::vector<Eigen::Vector2d> floorCentres(int n) {
  std::vector<Eigen::Vector2d> c;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) c.emplace_back(25.0 * x, 25.0 * y);
  return c;
}

// An n x n floor with one 50 x 50 mm mobile of 20 g at `at`, as a world file would give it.
std::unique_ptr<Simulation> floorWithMobile(int n, Eigen::Vector2d at, std::vector<ObstacleSpec> obstacles = {},
                                            SimTime step = kMillisecond) {
  std::vector<Cell> cells;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) cells.push_back(Cell{x, y, 0});
  auto sim = testsupport::makeSmart({n, n, 1}, cells);
  MobileSpec m;
  m.xMm = at.x();
  m.yMm = at.y();
  AirJetModel model;
  model.step = step;
  sim->setPhysics(std::make_unique<Physics>(floorCentres(n), std::vector<MobileSpec>{m}, std::move(obstacles), model));
  return sim;
}

}  // namespace

BOOST_AUTO_TEST_CASE(one_jet_under_the_mobile_reaches_the_terminal_speed_of_force_over_drag) {
  // Block 5 (1,1) at (25, 25) mm is under the mobile centred there; its east jet at full power for
  // 2 s. With a reach so long that the jet keeps its whole force as the mobile leaves it (f1 within
  // 2e-4 of 1), the speed tends to Fmax / c = 0.005 / 0.05 = 0.1 m/s (time constant m / c =
  // 0.4 s); the force acts along the line through the centre: no turn.
  AirJetModel model;
  model.reachMm = 1e6;
  Physics p(floorCentres(4), {MobileSpec{25, 25, 0, 50, 50, 0.02}}, {}, model);
  p.setJet(5, kEast, Eigen::Vector2d(1, 0), 1.0, 2 * kSecond);
  SimTime t = 0;
  for (; t < 2 * kSecond; t += kMillisecond) BOOST_REQUIRE(p.step(t));
  BOOST_CHECK_CLOSE(p.mobile(0).velocity.x(), 0.1, 1.0);  // 5 time constants: within 1 %
  BOOST_CHECK_SMALL(p.mobile(0).velocity.y(), 1e-12);
  BOOST_CHECK_SMALL(p.mobile(0).angularVelocity, 1e-12);
  // Then it glides to rest and the physics stops by itself.
  const double x = p.positionMm(0).x();
  while (p.step(t)) t += kMillisecond;
  BOOST_CHECK_LT(t, 10 * kSecond);
  // Coasting from 0.1 m/s with drag c: 0.1 * m / c = 40 mm more, give or take the valve's fall.
  BOOST_CHECK_CLOSE(p.positionMm(0).x() - x, 40.0, 3.0);
}

BOOST_AUTO_TEST_CASE(a_jet_out_of_reach_does_nothing_and_one_off_centre_turns_the_mobile) {
  // The mobile covers x, y in [0, 50]: block (3,0) at (75, 0) is 25 mm from its edge (out of
  // reach, 25 mm); block (2,0) at (50, 0) touches its corner: pushing north there turns it
  // counter-clockwise (a force at the right of the centre, northwards).
  Physics far(floorCentres(4), {MobileSpec{25, 25, 0, 50, 50, 0.02}}, {}, AirJetModel{});
  far.setJet(3, kNorth, Eigen::Vector2d(0, 1), 1.0, kSecond);
  for (SimTime t = 0; t < 100 * kMillisecond; t += kMillisecond) far.step(t);
  BOOST_CHECK_SMALL(far.mobile(0).velocity.norm(), 1e-12);
  Physics near(floorCentres(4), {MobileSpec{25, 25, 0, 50, 50, 0.02}}, {}, AirJetModel{});
  near.setJet(2, kNorth, Eigen::Vector2d(0, 1), 1.0, kSecond);
  for (SimTime t = 0; t < 100 * kMillisecond; t += kMillisecond) near.step(t);
  BOOST_CHECK_GT(near.mobile(0).velocity.y(), 0);
  BOOST_CHECK_GT(near.mobile(0).angularVelocity, 0);
}

BOOST_AUTO_TEST_CASE(an_obstacle_stops_the_mobile) {
  // A wall at x = 100 mm (a 10 mm wide obstacle centred at 105): the mobile pushed east stops with
  // its east edge (x + 25) at the wall, give or take one step.
  Physics p(floorCentres(8), {MobileSpec{25, 25, 0, 50, 50, 0.02}}, {ObstacleSpec{105, 25, 10, 200}}, AirJetModel{});
  for (SimTime t = 0; t < 3 * kSecond; t += kMillisecond) {
    for (std::uint32_t b = 8; b < 16; ++b)  // the row y = 1 blows east all the time
      p.setJet(b, kEast, Eigen::Vector2d(1, 0), 1.0, t + 2 * kMillisecond);
    p.step(t);
  }
  BOOST_CHECK_LE(p.positionMm(0).x() + 25.0, 100.0 + 1e-9);
  BOOST_CHECK_GT(p.positionMm(0).x() + 25.0, 99.0);
}

BOOST_AUTO_TEST_CASE(blocks_hear_the_mobile_arrive_and_leave_and_the_run_ends) {
  // A 4x4 floor, the mobile at (25, 25) covers blocks (0..2, 0..2)'s centres in [0, 50]^2: nine.
  // Block 5 (1,1) blows east for 300 ms: the mobile moves on and some blocks hear it leave.
  auto sim = floorWithMobile(4, {25, 25});
  Script s(*sim);
  s.onStart = [&](vs_ctx* c) {
    if (c->block == 5) BOOST_CHECK_EQUAL(c->api->air_jet(c, kEast, 1.0, 300 * kMillisecond), VS_OK);
  };
  sim->runUntilEmpty();
  std::size_t arrived = 0, left = 0;
  for (const testsupport::Rec& r : s.log)
    if (r.kind == VS_EV_MOBILE) (r.values[1] ? arrived : left)++;
  // What the blocks heard adds up to what the physics says is covered now.
  std::size_t covered = 0;
  for (std::uint32_t b = 0; b < 16; ++b) covered += sim->physics()->mobileOver(b) == 0;
  BOOST_CHECK_EQUAL(arrived - left, covered);
  BOOST_CHECK_GE(arrived, 9u);  // the nine at the start, then those it comes over
  BOOST_CHECK_GE(left, 3u);     // it moved more than 25 mm east: the west column is left
  BOOST_CHECK_GT(sim->physics()->positionMm(0).x(), 50.0);
  BOOST_CHECK_GT(sim->statistics().eventsByKind[std::size_t(EventKind::PhysicsStep)], 300u);
}

BOOST_AUTO_TEST_CASE(the_services_refuse_bad_requests_and_worlds_without_physics) {
  auto sim = floorWithMobile(3, {25, 25});
  Script s(*sim);
  std::vector<int> codes;
  s.onStart = [&](vs_ctx* c) {
    if (c->block != 0) return;
    std::int32_t mobile = -1;
    double at[3];
    codes.push_back(c->api->mobile_above(c, &mobile, at));
    BOOST_CHECK_EQUAL(mobile, 0);
    BOOST_CHECK(std::fabs(at[0] - 25) < 1e-9 && std::fabs(at[1] - 25) < 1e-9);
    codes.push_back(c->api->air_jet(c, 7, 1.0, kSecond));
    codes.push_back(c->api->air_jet(c, kEast, 1.5, kSecond));
    codes.push_back(c->api->air_jet(c, kEast, 0.5, -1));
  };
  sim->runUntilEmpty();
  BOOST_CHECK((codes == std::vector<int>{VS_OK, VS_ERR_BAD_FACE, VS_ERR_BAD_ARGUMENT, VS_ERR_BAD_ARGUMENT}));
  auto plain = testsupport::makeSmart({2, 1, 1}, {{0, 0, 0}, {1, 0, 0}});
  Script p(*plain);
  int rc = 0;
  p.onStart = [&](vs_ctx* c) { rc = c->api->air_jet(c, kEast, 1.0, kSecond); };
  plain->runUntilEmpty();
  BOOST_CHECK_EQUAL(rc, VS_ERR_UNSUPPORTED);
  BOOST_CHECK_THROW(testsupport::makeBlinky({1, 1, 1}, {{0, 0, 0}})
                        ->setPhysics(std::make_unique<Physics>(floorCentres(1), std::vector<MobileSpec>{MobileSpec{}},
                                                               std::vector<ObstacleSpec>{}, AirJetModel{})),
                    std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(world_files_describe_mobiles_and_obstacles_with_positions_in_errors) {
  const WorldDescription w = parseWorldXml(R"(<world gridSize="4,4,1" target="smartblocks">
  <blockList><blocksBox origin="0,0,0" size="4,4,1"/></blockList>
  <mobileList><mobile position="25,30" size="40,20" mass="0.05" angle="30"/></mobileList>
  <obstacleList><obstacle position="80,10" size="10,40"/></obstacleList>
</world>)",
                                           "w.xml");
  BOOST_REQUIRE_EQUAL(w.mobiles.size(), 1u);
  BOOST_CHECK_EQUAL(w.mobiles[0].spec.yMm, 30);
  BOOST_CHECK_EQUAL(w.mobiles[0].spec.lyMm, 20);
  BOOST_CHECK_EQUAL(w.mobiles[0].spec.massKg, 0.05);
  BOOST_CHECK_EQUAL(w.mobiles[0].spec.angleDeg, 30);
  BOOST_REQUIRE_EQUAL(w.obstacles.size(), 1u);
  BOOST_CHECK_EQUAL(w.obstacles[0].spec.lyMm, 40);
  const char* bad[][2] = {
      {R"(<world gridSize="2,2,1"><blockList><block position="0,0,0"/></blockList>
<mobileList><mobile position="1"/></mobileList></world>)",
       "w.xml:2:21: error: attribute 'position' of <mobile>: \"1\" is not two numbers (like 75,425)"},
      {R"(<world gridSize="2,2,1"><blockList><block position="0,0,0"/></blockList>
<mobileList><mobile position="1,2" mass="-3"/></mobileList></world>)",
       "w.xml:2:36: error: attribute 'mass' of <mobile>: \"-3\" is not a positive number"},
      {R"(<world gridSize="2,2,1"><blockList><block position="0,0,0"/></blockList>
<obstacleList><obstacle position="1,2"/></obstacleList></world>)",
       "w.xml:2:15: error: <obstacle> needs attribute 'size'"},
  };
  for (const auto& [text, message] : bad) {
    try {
      parseWorldXml(text, "w.xml");
      BOOST_ERROR("accepted: " << text);
    } catch (const XmlWorldError& e) {
      BOOST_CHECK_MESSAGE(std::string(e.what()).find(message) == 0, e.what() << " (wanted " << message << ")");
    }
  }
  // Mobiles on Blinky Blocks: refused where the list is.
  const WorldDescription blinky = parseWorldXml(R"(<world gridSize="2,2,1" target="blinkyblocks">
<blockList><block position="0,0,0"/></blockList>
<mobileList><mobile position="1,2"/></mobileList></world>)",
                                                "b.xml");
  auto sim = testsupport::makeBlinky({2, 2, 1}, {});
  try {
    populateSimulation(blinky, *sim);
    BOOST_ERROR("mobiles on Blinky Blocks accepted");
  } catch (const XmlWorldError& e) {
    BOOST_CHECK_MESSAGE(std::string(e.what()).find("b.xml:3:13: error: <mobileList>: mobiles ride on a surface of "
                                                   "Smart Blocks, not on blinkyblocks") == 0,
                        e.what());
  }
}
