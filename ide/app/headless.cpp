#include "headless.hpp"

#include <QDir>
#include <QImage>
#include <cstdio>
#include <iostream>

#include "frame_export.hpp"
#include "offscreen_render.hpp"
#include "sim_controller.hpp"

namespace ide {

namespace {

int openFailure(const SimController& controller) {
  std::cerr << controller.diagnostics();
  const std::string& e = controller.error();
  std::cerr << (e.find(": error: ") != std::string::npos ? "" : "vsim-ide: error: ") << e << '\n';
  return controller.errorCode();
}

int framesFromTheCommandLine(const IdeOptions& o) {
  FrameExport how;
  how.folder = o.framesDir;
  how.every = o.frameEvery;
  how.size = o.size;
  const FrameExportResult r = exportFrames(o.run, how);
  if (!r.error.empty()) {
    std::cerr << (r.error.find(": error: ") != std::string::npos ? "" : "vsim-ide: error: ") << r.error
              << '\n';
    return r.exitCode;
  }
  if (!o.run.quiet)
    std::printf("frames: %d written to %s, one every %s of simulated time\n", r.written, o.framesDir.c_str(),
                simcore::formatTime(o.frameEvery).c_str());
  return vsim::kExitOk;
}

}  // namespace

int runHeadless(const IdeOptions& o) {
  if (!o.framesDir.empty()) return framesFromTheCommandLine(o);
  SimController controller;
  if (!controller.open(o.run)) return openFailure(controller);
  OffscreenRenderer renderer;
  QString error;
  if (!renderer.initialize(controller.info(), o.size, error)) {
    std::cerr << "vsim-ide: error: cannot render: " << error.toStdString() << '\n';
    return vsim::kExitRuntime;
  }
  const auto snap = controller.runToAndWait(o.run.until.value_or(simcore::kTimeInfinity));
  if (snap->state == RunState::Failed) {
    std::cerr << "vsim-ide: error: the run failed at " << simcore::formatTime(snap->now) << ": "
              << snap->error << '\n';
    return vsim::kExitRuntime;
  }
  const OrbitCamera camera = initialCamera(controller.info(), *snap);
  const QImage image = renderer.render(*snap, camera);
  if (image.isNull() || !image.save(QString::fromStdString(o.screenshot), "PNG")) {
    std::cerr << "vsim-ide: error: cannot write '" << o.screenshot << "'\n";
    return vsim::kExitRuntime;
  }
  if (o.frameTimes)
    std::printf("frame time: %.2f ms (%d frames of %dx%d, %zu blocks)\n",
                renderer.timeFrames(*snap, camera, o.frameTimes), o.frameTimes, o.size.width(),
                o.size.height(), controller.info().blockCount);
  if (!o.run.quiet)
    std::printf("screenshot: %s (%dx%d) at %s, %llu events, fingerprint %016llx\n", o.screenshot.c_str(),
                image.width(), image.height(), simcore::formatTime(snap->now).c_str(),
                static_cast<unsigned long long>(snap->events),
                static_cast<unsigned long long>(snap->fingerprint));
  return vsim::kExitOk;
}

}  // namespace ide
