# meld_add_blockcode(NAME SOURCE... [POLLING]): a C BlockCode, the shared object that
# `vsim --code NAME.so` (or a world's code="NAME.so") loads. No "lib" prefix, so that the file is
# named as worlds name it; POLLING links the polling library (blockcode_polling.h) as well.
# Used by this repository's examples and, through find_package(MeldToolchain), by BlockCodes
# built outside it: one definition for both.
function(meld_add_blockcode name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "POLLING" "" "")
  if(NOT ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "meld_add_blockcode(${name}): no source files given")
  endif()
  add_library(${name} MODULE ${ARG_UNPARSED_ARGUMENTS})
  target_link_libraries(${name} PRIVATE MeldToolchain::blockcode)
  if(ARG_POLLING)
    target_link_libraries(${name} PRIVATE MeldToolchain::blockcode_polling)
  endif()
  set_target_properties(${name} PROPERTIES PREFIX "" POSITION_INDEPENDENT_CODE ON)
endfunction()
