# Checks that every C++ source under SRC is as clang-format (the project's .clang-format) writes
# it. Usage: cmake -DSRC=<folder> -DCLANG_FORMAT=<program> -P check_format.cmake
# Exits non-zero naming each file that differs; `make format` rewrites them.
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format not found: scripts/setup.sh installs it (Debian package clang-format)")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/cxx_sources.cmake)
list(FILTER files EXCLUDE REGEX "^tests/style/misformatted/")  # the fixture, wrong on purpose
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no C++ sources under ${SRC}")
endif()
execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror --style=file ${files} WORKING_DIRECTORY ${SRC}
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  string(REGEX MATCHALL "[^\n]*: error: code should be clang-formatted" lines "${err}")
  set(named)
  foreach(l IN LISTS lines)
    string(REGEX REPLACE ":[0-9]+:[0-9]+: error: code should be clang-formatted" "" f "${l}")
    list(APPEND named ${f})
  endforeach()
  list(REMOVE_DUPLICATES named)
  list(JOIN named "\n  " named)
  message(FATAL_ERROR "not clang-formatted (run `make format`):\n  ${named}")
endif()
message(STATUS "${count} C++ files are clang-formatted")
