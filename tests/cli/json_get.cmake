# cmake -DFILE=report.json -DKEYS="a;b.c" -P json_get.cmake
# Prints key=value for each (dotted) key; fails if the file is not valid JSON or a key is missing.
# CMake's own JSON parser keeps the tests free of python or jq.
file(READ "${FILE}" json)
foreach(key ${KEYS})
  string(REPLACE "." ";" path "${key}")
  string(JSON value ERROR_VARIABLE error GET "${json}" ${path})
  if(error)
    message(FATAL_ERROR "${FILE}: ${key}: ${error}")
  endif()
  message(STATUS "${key}=${value}")
endforeach()
