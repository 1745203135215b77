# `cmake --install BUILD [--prefix P]`: the programs in P/bin, the Meld standard library in
# P/share/meld/stdlib (meldc finds it there, relative to its own location), the block ABI headers in
# P/include/simcore with the polling library in P/lib, the example BlockCodes in
# P/lib/meld/blockcodes (vsim finds worlds' `code="name.so"` there), the examples in
# P/share/meld/examples, the documents in P/share/doc/meld-toolchain, and what a BlockCode built
# elsewhere needs: the CMake package (find_package(MeldToolchain)) and the pkg-config files. The man
# pages are man.cmake's. Every path is relative to the prefix.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
# Fixed, not GNUInstallDirs' LIBDIR: vsim looks for <bin>/../lib/meld/blockcodes.
set(MELD_BLOCKCODE_DIR lib/meld/blockcodes)
set(MELD_STDLIB_DIR ${CMAKE_INSTALL_DATADIR}/meld/stdlib)
set(MELD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/MeldToolchain)

install(TARGETS meldc meld vsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The JIT (meld --jit, vsim --jit) as a module, where both look for it: <bin>/../lib/meld.
install(TARGETS meld_jit LIBRARY DESTINATION lib/meld)
# So does meld's front end for .meld files (libmeld_frontend.so).
install(TARGETS meld_frontend LIBRARY DESTINATION lib/meld)
if(TARGET vsim-ide)
  install(TARGETS vsim-ide RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/stdlib/ DESTINATION ${MELD_STDLIB_DIR}
        FILES_MATCHING PATTERN "*.meld" PATTERN "README.md")
install(FILES ${PROJECT_SOURCE_DIR}/simcore/abi/include/simcore/blockcode.h
              ${PROJECT_SOURCE_DIR}/simcore/abi/include/simcore/blockcode_polling.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/simcore)
install(TARGETS color_flood tap_cycle brownian_flood brownian_epidemic wave_events wave_polling conveyor
        LIBRARY DESTINATION ${MELD_BLOCKCODE_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/worlds ${PROJECT_SOURCE_DIR}/examples/meld
                  ${PROJECT_SOURCE_DIR}/examples/c ${PROJECT_SOURCE_DIR}/examples/physics
                  ${PROJECT_SOURCE_DIR}/examples/blockcode-project
        DESTINATION ${CMAKE_INSTALL_DATADIR}/meld/examples)

# The documents (user guide, language reference, world format, block ABI, architecture).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/meld-toolchain
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png")

# The CMake package: MeldToolchain::blockcode (the ABI header) and ::blockcode_polling.
install(TARGETS blockcode_abi blockcode_polling EXPORT MeldToolchainTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT MeldToolchainTargets NAMESPACE MeldToolchain:: DESTINATION ${MELD_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/MeldToolchainConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/MeldToolchainConfig.cmake
                              INSTALL_DESTINATION ${MELD_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_INCLUDEDIR CMAKE_INSTALL_BINDIR MELD_BLOCKCODE_DIR
                                        MELD_STDLIB_DIR)
# 0.x: a minor version may change the ABI's helpers, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/MeldToolchainConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/MeldToolchainConfig.cmake
              ${PROJECT_BINARY_DIR}/MeldToolchainConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/MeldBlockCode.cmake
        DESTINATION ${MELD_CMAKE_DIR})

# pkg-config: relocatable (the prefix is found from the .pc file's own folder).
file(RELATIVE_PATH MELD_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" MELD_PC_TO_PREFIX "${MELD_PC_TO_PREFIX}")
foreach(pc IN ITEMS meld-blockcode meld-blockcode-polling)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
