// vsim-ide --screenshot, run as a user would: a world whose blocks a program colours in two
// colours (tests/ide/two-colors.*: green at first, then red on even columns and blue on odd ones)
// gives a PNG of the requested size, both colours over about the same area, and no green left.
#include <QDir>
#include <QImage>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>
#include <array>

namespace {

const QString kSource = MELD_SOURCE_DIR;
const QString kIde = QString(MELD_BINARY_DIR) + "/ide/vsim-ide";

enum class Hue { Red, Blue, Green, Other };

// By the dominant channel, so that lit and shaded faces of one colour count the same.
Hue hueOf(QRgb p) {
  const int r = qRed(p), g = qGreen(p), b = qBlue(p);
  if (r > 60 && r > 2 * std::max(g, b)) return Hue::Red;
  if (b > 60 && b > 2 * std::max(r, g)) return Hue::Blue;
  if (g > 60 && g > 2 * std::max(r, b)) return Hue::Green;
  return Hue::Other;
}

}  // namespace

class ScreenshotTest : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void twoColoursInTheirProportion() {
    QTemporaryDir dir;
    const QString png = dir.filePath("two.png");
    QProcess p;
    p.start(kIde, {kSource + "/tests/ide/two-colors.xml", "--screenshot", png, "--size", "400x300"});
    QVERIFY(p.waitForFinished(60000));
    QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
    QVERIFY(QString::fromUtf8(p.readAllStandardOutput()).contains("screenshot: "));
    const QImage image(png);
    QCOMPARE(image.size(), QSize(400, 300));
    long red = 0, blue = 0, green = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) switch (hueOf(image.pixel(x, y))) {
          case Hue::Red:
            ++red;
            break;
          case Hue::Blue:
            ++blue;
            break;
          case Hue::Green:
            ++green;
            break;
          case Hue::Other:
            break;
        }
    qInfo("red %ld, blue %ld, green %ld pixels", red, blue, green);
    QCOMPARE(green, 0L);
    QVERIFY(red > 400 * 300 / 10);  // the blocks cover a good part of the picture
    const double ratio = double(red) / double(std::max(blue, 1L));
    QVERIFY2(ratio > 0.85 && ratio < 1.15, qPrintable(QString("red/blue = %1").arg(ratio)));
  }

  void theWorldAsItIsAtTheTimeAsked() {
    // --until T shows the world after the events at T: the two-colour program colours every block
    // at time 0 already (green is gone at --until 0); the gradient example's blocks are white
    // until the tap at 1 s (no red at 0.5 s) and have a red centre after it.
    auto hues = [&](const QStringList& args) {
      QTemporaryDir dir;
      const QString png = dir.filePath("at.png");
      QProcess p;
      p.start(kIde, QStringList(args) << "--screenshot" << png << "--size"
                                      << "200x150"
                                      << "--quiet");
      p.waitForFinished(60000);
      std::array<long, 4> n{};
      if (p.exitCode() != 0) return n;
      const QImage image(png);
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) ++n[std::size_t(hueOf(image.pixel(x, y)))];
      return n;
    };
    const auto two = hues({kSource + "/tests/ide/two-colors.xml", "--until", "0"});
    QCOMPARE(two[std::size_t(Hue::Green)], 0L);
    QVERIFY(two[std::size_t(Hue::Red)] > 0 && two[std::size_t(Hue::Blue)] > 0);
    const auto before = hues({kSource + "/examples/worlds/meld-gradient-tap.xml", "--until", "500ms"});
    QCOMPARE(before[std::size_t(Hue::Red)], 0L);
    QVERIFY(before[std::size_t(Hue::Other)] > 0);
    const auto after = hues({kSource + "/examples/worlds/meld-gradient-tap.xml", "--until", "2s"});
    QVERIFY(after[std::size_t(Hue::Red)] > 0);
  }

  void framesEveryDeltaT() {
    // The gradient example: white blocks until the tap at 1 s, the run over at about 1.01 s. A
    // frame at 0, 0.4, 0.8 and 1.2 s (the end): no red before the tap, red after.
    QTemporaryDir dir;
    QProcess p;
    p.start(kIde, {kSource + "/examples/worlds/meld-gradient-tap.xml", "--frames", dir.filePath("f"),
                   "--every", "400ms", "--size", "160x120"});
    QVERIFY(p.waitForFinished(60000));
    QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
    QVERIFY(QString::fromUtf8(p.readAllStandardOutput()).contains("frames: 4 written"));
    const QStringList frames = QDir(dir.filePath("f")).entryList({"frame-*.png"}, QDir::Files, QDir::Name);
    QCOMPARE(frames.size(), 4);
    auto reds = [&](const QString& name) {
      const QImage image(dir.filePath("f/" + name));
      long n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) n += hueOf(image.pixel(x, y)) == Hue::Red;
      return n;
    };
    QCOMPARE(reds(frames[0]), 0L);
    QCOMPARE(reds(frames[2]), 0L);
    QVERIFY(reds(frames[3]) > 0);
  }

  void badInputExitsWithAMessage() {
    QProcess p;
    p.start(kIde, {kSource + "/no/such.xml", "--screenshot", "x.png"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 3);
    QVERIFY(p.readAllStandardError().contains("cannot open world file"));
    p.start(kIde, {kSource + "/tests/ide/two-colors.xml", "--screenshot", "x.png", "--size", "big"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 2);
    QVERIFY(p.readAllStandardError().contains("--size wants"));
    p.start(kIde, {kSource + "/tests/ide/two-colors.xml", "--frames", "d", "--every", "0s"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 2);
    QVERIFY(p.readAllStandardError().contains("--every wants a positive duration"));
    // A .so that is not a BlockCode: an input error (exit 3), as vsim says it.
    p.start(kIde, {kSource + "/examples/worlds/color-flood.xml", "--code", kSource + "/README.md",
                   "--screenshot", "x.png"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 3);
    // No display: a message and exit 1, not Qt's abort.
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.remove("DISPLAY");
    env.remove("WAYLAND_DISPLAY");
    env.remove("QT_QPA_PLATFORM");
    p.setProcessEnvironment(env);
    p.start(kIde, {kSource + "/tests/ide/two-colors.xml", "--screenshot", "x.png"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 1);
    QVERIFY(p.readAllStandardError().contains("no display"));
  }
};

QTEST_GUILESS_MAIN(ScreenshotTest)
#include "qtest_screenshot.moc"
