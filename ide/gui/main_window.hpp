// The IDE's window: program editor | 3D world | block inspector side by side (splitters; the
// layout is kept from one run of the IDE to the next), the console below; the run's controls in
// the toolbar and its state in the status bar. The run itself lives in a SimController: the
// window polls its snapshots on a timer and never touches the simulation.
#pragma once

#include <QMainWindow>
#include <QPointer>
#include <memory>

#include "options.hpp"
#include "profile_runner.hpp"
#include "sim_controller.hpp"

class QComboBox;
class QLabel;
class QListWidget;
class QSplitter;
class QTimer;

namespace ide {

class BlockInspector;
class CodeEditor;
class ConsolePanel;
class WorldView;

// What the window does once the run is open (vsim-ide's --run and --select; vsim's --why makes it
// record derivations and show that fact's tree when the run ends).
struct StartActions {
  bool run = false;
  std::uint32_t select = 0xFFFFFFFFu;
};

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(const vsim::Options& options, const StartActions& start = {},
                      QWidget* parent = nullptr);
  ~MainWindow() override;

  // The parts, for tests.
  SimController& controller() { return controller_; }
  CodeEditor* editor() const { return editor_; }
  WorldView* worldView() const { return view_; }
  BlockInspector* inspector() const { return inspector_; }
  ConsolePanel* console() const { return console_; }
  QListWidget* diagnosticsList() const { return diagnostics_; }
  QString statusText() const;

  // The actions of the toolbar and menus, callable directly.
  bool openWorld(const QString& path);
  bool openProgram(const QString& path);
  // Saves the program and compiles it; the diagnostics are listed and underlined. True if clean.
  bool compile();
  // Compiles (if a program is open) and starts the run again from the beginning.
  bool restart();
  void selectBlock(std::uint32_t block);
  // Applies the newest snapshot and console lines now (the timer does it 30 times a second).
  void poll();
  bool saveScreenshot(const QString& path);
  // Opens `meld --profile` files in a profile window (several: with their speedup table); the
  // window, or nullptr after a message saying which file could not be read.
  QWidget* openProfiles(const QStringList& paths);
  // Run > Profile on threads: the editor's program (compiled as `meld` compiles it) at each
  // thread count, in the background; the profile window opens when the runs are over. False
  // (said in the console) with no program, compile errors, or runs already going.
  bool profileProgram(const std::vector<unsigned>& threads = ProfileRunner::defaultThreadCounts());
  // Run > Stop profiling: the run in progress stops after its current rule, the rest do not
  // start, no profile window opens. False (said in the console) when nothing runs.
  bool stopProfiling();
  // The window the last profiling opened (nullptr until then), for tests.
  QWidget* lastProfileWindow() const { return lastProfileWindow_; }
  // The run from its start, a frame every `every` of simulated time, seen from the view's camera,
  // into `folder` (frame-000000.png ...); the number written, -1 on error (said in the console).
  int exportFrames(const QString& folder, simcore::SimTime every);

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  void buildLayout();
  void buildFileMenu();  // main_window_actions.cpp, with the toolbars
  void buildRunActions();
  void buildBlockActions();
  template <class Slot>
  QAction* action(const QString& text, const QKeySequence& shortcut, const QString& tip, Slot slot);
  void showSession();
  void showDiagnostics(const QString& text);
  void addRecent(const QString& key, const QString& path);
  void refreshRecentMenu();
  double chosenSpeed() const;
  // Opens `file` in the editor (unless it is there) at line:column.
  void showSource(const QString& file, int line, int column);
  void runUntilAsked();
  void exportFramesAsked();

  SimController controller_;
  vsim::Options options_;
  CodeEditor* editor_;
  QListWidget* diagnostics_;
  QWidget* editorPane_;
  WorldView* view_;
  BlockInspector* inspector_;
  ConsolePanel* console_;
  QSplitter* splitter_;
  QComboBox* speed_;
  QLabel* status_;
  QMenu* recentMenu_ = nullptr;
  QTimer* timer_;
  std::uint32_t selected_ = 0xFFFFFFFFu;
  std::uint64_t shownSerial_ = 0, shownSession_ = 0;
  bool drawingFastest_ = false;  // the last snapshot shown was of a running run
  bool whyAtEnd_ = false;        // --why: ask once the run is over
  ProfileRunner profiler_;
  QString profileFolder_;
  QPointer<QWidget> lastProfileWindow_;
  void takeProfiles();
};

}  // namespace ide
