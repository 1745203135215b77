// The IDE's "as fast as possible" against headless: the same run (world, program, options) once
// straight through a vsim Session (what `vsim` does) and once in vsim-ide's window, shown and
// drawing, from the Run command to the end. Prints the events, both wall times and events/s, and
// their ratio (the goal: the IDE at least half of headless), and checks that both fingerprints are
// the same. Run under xvfb-run (bench/ide/run-ide-speed.sh does).
//   ide_speed WORLD.xml [vsim run options, e.g. --program P.meld --tap 0@1ms]
#include <QApplication>
#include <QElapsedTimer>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTest>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "gl_setup.hpp"
#include "main_window.hpp"
#include "session.hpp"
#include "world_view.hpp"

namespace {

struct Measure {
  std::uint64_t events = 0, fingerprint = 0;
  double wall = 0;
};

Measure headless(const vsim::Options& o) {
  vsim::Session s(o, vsim::SessionStreams{});
  const auto start = std::chrono::steady_clock::now();
  s.simulation().run();
  Measure m;
  m.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.events = s.simulation().statistics().eventsProcessed;
  m.fingerprint = s.simulation().fingerprint();
  return m;
}

Measure inWindow(const vsim::Options& o, double& frameMs) {
  ide::MainWindow w(o);
  w.resize(1280, 800);
  w.show();
  if (!QTest::qWaitForWindowExposed(&w)) throw std::runtime_error("the window was not shown");
  QTest::qWait(300);  // first frames drawn, before the clock starts
  QElapsedTimer timer;
  timer.start();
  w.controller().run(0);
  // The window's own timer polls and draws as it would for a user; this loop only sleeps in the
  // event loop and looks at the end without asking for snapshots (that would cost the kernel).
  auto over = [](const ide::WorldSnapshot& s) {
    return s.state == ide::RunState::Finished || s.state == ide::RunState::Failed;
  };
  std::shared_ptr<const ide::WorldSnapshot> s;
  while (!(s = w.controller().waitFor(over, std::chrono::milliseconds(0)))) QTest::qWait(5);
  Measure m;
  m.wall = double(timer.nsecsElapsed()) / 1e9;
  m.events = s->events;
  m.fingerprint = s->fingerprint;
  frameMs = w.worldView()->frameMs();
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  vsim::Options o;
  try {
    o = vsim::parseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "ide_speed: " << e.what() << "\nusage: ide_speed WORLD.xml [vsim run options]\n";
    return 2;
  }
  ide::setUpOpenGl();
  QApplication app(argc, argv);
  QStandardPaths::setTestModeEnabled(true);
  try {
    const Measure h = headless(o);
    double frameMs = 0;
    const Measure i = inWindow(o, frameMs);
    std::printf("events            %llu\n", static_cast<unsigned long long>(h.events));
    std::printf("headless          %.3f s  %.0f events/s\n", h.wall, double(h.events) / h.wall);
    std::printf("ide, fastest      %.3f s  %.0f events/s  (frame submit %.2f ms)\n", i.wall,
                double(i.events) / i.wall, frameMs);
    std::printf("ide / headless    %.2f\n", (double(i.events) / i.wall) / (double(h.events) / h.wall));
    std::printf("fingerprints      %016llx %016llx %s\n", static_cast<unsigned long long>(h.fingerprint),
                static_cast<unsigned long long>(i.fingerprint),
                h.fingerprint == i.fingerprint ? "same" : "DIFFER");
    return h.fingerprint == i.fingerprint && h.events == i.events ? 0 : 1;
  } catch (const vsim::SessionError& e) {
    std::cerr << "ide_speed: " << e.message << '\n';
    return 3;
  }
}
