#include "gl_setup.hpp"

#include <QByteArray>
#include <QSurfaceFormat>
#include <QtGlobal>
#include <algorithm>
#include <string>
#include <thread>

namespace ide {

void setUpOpenGl() {
  if (!qEnvironmentVariableIsSet("LP_NUM_THREADS")) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    qputenv("LP_NUM_THREADS", QByteArray::number(std::max(1u, cores - 1)));
  }
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);
}

}  // namespace ide
