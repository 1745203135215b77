# Man pages: each program's page is written from its own --help and --version at build time
# (help_to_man.py), so that the page and --help say the same; installed in share/man/man1.
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(MELD_MAN_PAGES)
function(meld_man_page program summary)
  set(page ${PROJECT_BINARY_DIR}/man/${program}.1)
  add_custom_command(OUTPUT ${page}
                     COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/man
                     COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/help_to_man.py
                             $<TARGET_FILE:${program}> ${page} ${summary} ${ARGN}
                     DEPENDS ${program} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/help_to_man.py
                     COMMENT "Man page ${program}.1 from ${program} --help" VERBATIM)
  set(MELD_MAN_PAGES ${MELD_MAN_PAGES} ${page} PARENT_SCOPE)
endfunction()

meld_man_page(meldc "compile Linear Meld programs to bytecode or native code" meld vsim)
meld_man_page(meld "run a Meld program on its own graph of nodes" meldc vsim)
meld_man_page(vsim "simulate modular robots running a C BlockCode or a Meld program" meldc meld vsim-ide)
if(TARGET vsim-ide)
  meld_man_page(vsim-ide "the IDE: Meld program, 3D world and block inspector side by side" vsim meldc)
endif()
add_custom_target(man_pages ALL DEPENDS ${MELD_MAN_PAGES})
install(FILES ${MELD_MAN_PAGES} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
