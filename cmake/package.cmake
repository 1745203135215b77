# `cpack -G DEB` (in a build folder): the Debian package meld-toolchain, installed under /usr.
# Its run-time dependencies come from dpkg-shlibdeps on the programs (LLVM, Qt, ANTLR, pugixml);
# binutils is added by hand: `meldc --emit=native` links with the system's ld. Checked by the CTest
# test install.deb (built, unpacked into a throw-away root, the demo run from there).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME meld-toolchain)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "Meld toolchain project")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Linear Meld compiler, virtual machine and modular-robot simulator")
set(CPACK_PACKAGE_DESCRIPTION
    "meldc compiles Linear Meld programs to bytecode or native code (LLVM); meld runs them on their
own graph, on one or many threads; vsim simulates Blinky Blocks, Smart Blocks and Catoms 2D/3D
running a Meld program or a C BlockCode, and a simulated multicore chip; vsim-ide shows the
program, the facts and the 3D world side by side. With the block ABI's headers, the polling
library, a CMake package and pkg-config files for BlockCodes, examples and man pages.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(MELD_PACKAGE_MAINTAINER "Meld toolchain developers <meld-toolchain@localhost>"
    CACHE STRING "Maintainer field of the Debian package")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${MELD_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "binutils")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "gcc | c-compiler, cmake, pkg-config, xvfb")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/package)
set(CPACK_STRIP_FILES ON)
include(CPack)
