// The profile view of the multicore target: profiles that `meld -j N --profile` wrote for a
// program at 1 and 2 threads, and `vsim --target multicore --profile` for a simulated chip, are read back
// (spans, per-thread summary, the speedup table), the timeline draws them and zooms, and files that are not
// such profiles are refused with a reason. With PROFILE_VIEW_PNG set, the view is also saved there (the
// picture in the closing note).
#include <QImage>
#include <QProcess>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QWheelEvent>
#include <QtTest>

#include "profile_view.hpp"

using namespace ide;

class ProfileViewTest : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir dir_;
  QString profileAt(int threads) const { return dir_.filePath(QString("ring.j%1.json").arg(threads)); }
  // Writes `text` into the test's folder; returns the path (empty if it could not).
  QString write(const QString& name, const QByteArray& text) const {
    QFile f(dir_.filePath(name));
    if (!f.open(QIODevice::WriteOnly) || f.write(text) != text.size()) return {};
    return f.fileName();
  }

 private Q_SLOTS:
  void initTestCase() {
    // A ring of 64 nodes passing 200 tokens around 30 times: enough node runs for both threads.
    QString source = "type route edge(node, node).\ntype linear token(node, int).\n";
    for (int i = 0; i < 64; ++i) source += QString("!edge(@%1, @%2).\n").arg(i).arg((i + 1) % 64);
    for (int i = 0; i < 200; ++i) source += QString("token(@%1, 30).\n").arg(i % 64);
    source += "token(A, N), N > 0, !edge(A, B) -o token(B, N - 1).\n";
    const QString program = write("ring.meld", source.toUtf8());
    QVERIFY(!program.isEmpty());
    for (int threads : {1, 2}) {
      QProcess meld;
      meld.start(MELD_BINARY_DIR "/apps/meld/meld",
                 {program, "-j", QString::number(threads), "--profile", profileAt(threads)});
      QVERIFY(meld.waitForFinished(60000));
      QCOMPARE(meld.exitCode(), 0);
    }
    QProcess vsim;  // the same program on a simulated 4-core chip
    vsim.start(MELD_BINARY_DIR "/apps/vsim/vsim",
               {"--target", "multicore", "--program", program, "--cores", "4", "--quiet", "--profile",
                dir_.filePath("ring.chip4.json")});
    QVERIFY(vsim.waitForFinished(60000));
    QCOMPARE(vsim.exitCode(), 0);
  }

  void readsASimulatedChipsCores() {
    QString error;
    const std::optional<Profile> chip = loadProfile(dir_.filePath("ring.chip4.json"), error);
    QVERIFY2(chip, qPrintable(error));
    QCOMPARE(chip->title, QString("vsim multicore 4 cores"));
    QVERIFY(chip->simulated);
    QCOMPARE(int(chip->threads.size()), 4);
    QCOMPARE(chip->laneNames[3], QString("core 3"));
    unsigned long long facts = 0;
    for (const ThreadSummary& s : chip->summary) facts += s.facts;
    QCOMPARE(facts,
             6264ull);  // the same facts as on threads (the ring's result does not depend on the schedule)
    ProfileView view({*chip});
    QVERIFY(view.timeline() != nullptr);
  }

  void readsTheThreadsTheirSpansAndTheSweep() {
    QString error;
    const std::optional<Profile> one = loadProfile(profileAt(1), error),
                                 two = loadProfile(profileAt(2), error);
    QVERIFY2(one && two, qPrintable(error));
    QCOMPARE(one->title, QString("meld -j 1"));
    QCOMPARE(int(one->threads.size()), 1);
    QCOMPARE(int(two->threads.size()), 2);
    unsigned long long runs = 0;
    for (const ThreadSummary& s : two->summary) {
      runs += s.nodeRuns;
      QVERIFY(s.runUs + s.idleUs + s.stealUs <= two->endUs * 1.001);
    }
    QVERIFY(runs >= 64u);                      // every node ran at least once
    QCOMPARE(one->summary[0].facts, 6264ull);  // 64 edges, 200 tokens, 200 x 30 hops
    const std::vector<SweepRow> rows = sweep({*two, *one});
    QCOMPARE(int(rows.size()), 2);
    QCOMPARE(rows[0].threads, 1);
    QCOMPARE(rows[0].speedup, 1.0);
    QCOMPARE(rows[1].threads, 2);
    QVERIFY(std::abs(rows[1].efficiency - rows[1].speedup / 2) < 1e-9);
  }

  void showsTheTimelineTheSummaryAndZooms() {
    QString error;
    std::vector<Profile> profiles{*loadProfile(profileAt(1), error), *loadProfile(profileAt(2), error)};
    ProfileView view(std::move(profiles));
    view.resize(1000, 640);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QCOMPARE(view.summaryTable()->rowCount(), 2);  // the 2-thread run first
    QCOMPARE(view.sweepTable()->rowCount(), 2);
    QCOMPARE(view.sweepTable()->item(0, 2)->text(), QString("1.00"));
    // The timeline draws the run spans in green.
    const QImage picture = view.timeline()->grab().toImage();
    int green = 0;
    for (int y = 0; y < picture.height(); ++y)
      for (int x = 0; x < picture.width(); ++x) {
        const QColor c = picture.pixelColor(x, y);
        green += c.green() > c.red() + 30 && c.green() > c.blue() + 30;
      }
    QVERIFY2(green > 500, qPrintable(QString("%1 green pixels").arg(green)));
    if (qEnvironmentVariableIsSet("PROFILE_VIEW_PNG"))
      view.grab().save(qEnvironmentVariable("PROFILE_VIEW_PNG"));
    // The wheel zooms in around the mouse; a double click shows the whole run again.
    const double whole = view.timeline()->viewEnd() - view.timeline()->viewBegin();
    const QPointF at(500, 40);
    QWheelEvent wheel(at, view.timeline()->mapToGlobal(at), {}, {0, 120}, Qt::NoButton, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(view.timeline(), &wheel);
    QVERIFY(view.timeline()->viewEnd() - view.timeline()->viewBegin() < whole * 0.9);
    QTest::mouseDClick(view.timeline(), Qt::LeftButton, {}, QPoint(500, 40));
    QCOMPARE(view.timeline()->viewEnd() - view.timeline()->viewBegin(), whole);
  }

  void refusesWhatIsNotAProfile() {
    QString error;
    QVERIFY(!loadProfile(write("junk.json", "{\"traceEvents\": ["), error));
    QVERIFY2(error.contains("not JSON"), qPrintable(error));
    QVERIFY(!loadProfile(
        write("other.json",
              "{\"traceEvents\": [{\"name\": \"x\", \"ph\": \"X\", \"ts\": 1, \"dur\": 2, \"tid\": 0}]}"),
        error));
    QVERIFY2(error.contains("not a profile written by `meld --profile`"), qPrintable(error));
    QVERIFY(!loadProfile(dir_.filePath("missing.json"), error));
    QVERIFY2(error.contains("cannot read"), qPrintable(error));
  }
};

QTEST_MAIN(ProfileViewTest)
#include "qtest_profile_view.moc"
