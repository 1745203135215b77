# `cmake --install BUILD [--prefix P]`: the programs in P/bin, the Meld standard library in
# P/share/meld/stdlib (meldc finds it there, relative to its own location), the block ABI headers in
# P/include/simcore with the polling library in P/lib, the example BlockCodes in
# P/lib/meld/blockcodes (vsim finds worlds' `code="name.so"` there), and the examples in
# P/share/meld/examples. Issue 15 adds the package, the CMake/pkg-config files and the man pages.
include(GNUInstallDirs)
install(TARGETS meldc meld vsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET vsim-ide)
  install(TARGETS vsim-ide RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/stdlib/ DESTINATION ${CMAKE_INSTALL_DATADIR}/meld/stdlib
        FILES_MATCHING PATTERN "*.meld" PATTERN "README.md")
install(FILES ${PROJECT_SOURCE_DIR}/simcore/abi/include/simcore/blockcode.h
              ${PROJECT_SOURCE_DIR}/simcore/abi/include/simcore/blockcode_polling.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/simcore)
install(TARGETS blockcode_polling ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS color_flood tap_cycle brownian_flood brownian_epidemic wave_events wave_polling conveyor
        LIBRARY DESTINATION lib/meld/blockcodes)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/worlds ${PROJECT_SOURCE_DIR}/examples/meld
                  ${PROJECT_SOURCE_DIR}/examples/c ${PROJECT_SOURCE_DIR}/examples/physics
        DESTINATION ${CMAKE_INSTALL_DATADIR}/meld/examples)
