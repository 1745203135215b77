// vsim-ide: the IDE's window, or one picture of a run without a window (--screenshot).
#include <QApplication>
#include <iostream>

#include "gl_setup.hpp"
#include "headless.hpp"
#include "ide_options.hpp"
#include "main_window.hpp"

#ifndef VSIM_VERSION
#define VSIM_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  ide::IdeOptions options;
  try {
    options = ide::parseIdeOptions(argc, argv);
  } catch (const std::exception& e) {  // UsageError, TraceFilterError
    std::cerr << "vsim-ide: error: " << e.what() << '\n';
    return vsim::kExitUsage;
  }
  if (options.run.help) {
    std::cout << ide::ideUsageText();
    return 0;
  }
  if (options.run.version) {
    std::cout << "vsim-ide " VSIM_VERSION "\n";
    return 0;
  }
  // Without a display Qt aborts the process: say what to do instead.
  if (!qEnvironmentVariableIsSet("DISPLAY") && !qEnvironmentVariableIsSet("WAYLAND_DISPLAY") &&
      !qEnvironmentVariableIsSet("QT_QPA_PLATFORM")) {
    std::cerr << "vsim-ide: error: no display (DISPLAY is not set); without one, run it under Xvfb: "
                 "xvfb-run -a vsim-ide ...\n";
    return vsim::kExitRuntime;
  }
  ide::setUpOpenGl();  // before the application object, as Qt requires
  QApplication app(argc, argv);
  QApplication::setApplicationName("vsim-ide");
  QApplication::setOrganizationName("meld-toolchain");
  if (!options.screenshot.empty() || !options.framesDir.empty()) return ide::runHeadless(options);
  ide::StartActions start;
  start.run = options.runAtOnce;
  start.select = options.select;
  ide::MainWindow window(options.run, start);
  window.show();
  if (!options.profiles.empty()) {
    QStringList paths;
    for (const std::string& p : options.profiles) paths << QString::fromStdString(p);
    window.openProfiles(paths);
  }
  return app.exec();
}
