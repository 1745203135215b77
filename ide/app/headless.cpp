#include "headless.hpp"

#include <QImage>
#include <cstdio>
#include <iostream>

#include "offscreen_render.hpp"
#include "sim_controller.hpp"

namespace ide {

int takeScreenshot(const IdeOptions& o) {
  SimController controller;
  controller.setRecordDerivations(false);
  if (!controller.open(o.run)) {
    std::cerr << controller.diagnostics();
    const std::string& e = controller.error();
    std::cerr << (e.find(": error: ") != std::string::npos ? "" : "vsim-ide: error: ") << e << '\n';
    return e.find("--") == 0 || e.rfind("no block code", 0) == 0 ? vsim::kExitUsage : vsim::kExitInput;
  }
  const simcore::SimTime until = o.run.until.value_or(simcore::kTimeInfinity);
  controller.runUntil(until);
  auto done = [&](const WorldSnapshot& s) {
    return s.state == RunState::Finished || s.state == RunState::Failed ||
           (s.state == RunState::Paused && s.now >= until);
  };
  std::shared_ptr<const WorldSnapshot> snap;
  while (!(snap = controller.waitFor(done, std::chrono::seconds(1)))) {
  }
  if (snap->state == RunState::Failed) {
    std::cerr << "vsim-ide: error: the run failed at " << simcore::formatTime(snap->now) << ": "
              << snap->error << '\n';
    return vsim::kExitRuntime;
  }
  QString error;
  double msPerFrame = 0;
  const QImage image = renderOffscreen(controller.info(), *snap, initialCamera(controller.info(), *snap),
                                       o.size, error, o.frameTimes, &msPerFrame);
  if (image.isNull()) {
    std::cerr << "vsim-ide: error: cannot render: " << error.toStdString() << '\n';
    return vsim::kExitRuntime;
  }
  if (!image.save(QString::fromStdString(o.screenshot), "PNG")) {
    std::cerr << "vsim-ide: error: cannot write '" << o.screenshot << "'\n";
    return vsim::kExitRuntime;
  }
  if (o.frameTimes)
    std::printf("frame time: %.2f ms (%d frames of %dx%d, %zu blocks)\n", msPerFrame, o.frameTimes,
                o.size.width(), o.size.height(), controller.info().blockCount);
  if (!o.run.quiet)
    std::printf("screenshot: %s (%dx%d) at %s, %llu events, fingerprint %016llx\n", o.screenshot.c_str(),
                image.width(), image.height(), simcore::formatTime(snap->now).c_str(),
                static_cast<unsigned long long>(snap->events),
                static_cast<unsigned long long>(snap->fingerprint));
  return vsim::kExitOk;
}

}  // namespace ide
