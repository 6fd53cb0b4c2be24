# Checks that no function in the C++ sources under SRC is over MAX_LINES lines (default 120, issue
# 30: long pipelines are split into named phases), outside the data tables allowed below.
# Usage: cmake -DSRC=<folder> -DCTAGS=<universal-ctags> [-DMAX_LINES=120] -P check_function_length.cmake
# Exits non-zero naming each function over the limit as path:line name (lines). A function's
# lines are those universal-ctags gives it, from its name's line to its closing brace's.
cmake_minimum_required(VERSION 3.25)  # IN_LIST
if(NOT CTAGS)
  message(FATAL_ERROR "universal-ctags not found: scripts/setup.sh installs it (Debian package universal-ctags)")
endif()
if(NOT MAX_LINES)
  set(MAX_LINES 120)
endif()
# Data tables, exempt: path:function, each with why it is one.
set(allowed
    "tests/cli/hostile_input_test.cpp:cases"  # the hostile-input suite: a row per case (files, arguments, exit, message)
)
include(${CMAKE_CURRENT_LIST_DIR}/cxx_sources.cmake)
list(FILTER files EXCLUDE REGEX "^tests/style/long_function/")  # the fixture, too long on purpose
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no C++ sources under ${SRC}")
endif()
execute_process(COMMAND ${CTAGS} -x "--_xformat=%n:%e:%F:%N" --kinds-c++=f --fields=+ne --language-force=c++
                        ${files}
                WORKING_DIRECTORY ${SRC} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CTAGS} failed (${rc}): ${err}")
endif()
string(REPLACE "\n" ";" lines "${out}")
set(long)
set(functions 0)
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^([0-9]+):([0-9]+):([^:]+):(.+)$")
    continue()
  endif()
  math(EXPR functions "${functions} + 1")
  set(first ${CMAKE_MATCH_1})
  set(path ${CMAKE_MATCH_3})
  set(name ${CMAKE_MATCH_4})
  math(EXPR length "${CMAKE_MATCH_2} - ${first} + 1")
  if(length GREATER MAX_LINES AND NOT "${path}:${name}" IN_LIST allowed)
    list(APPEND long "${path}:${first} ${name} (${length} lines)")
  endif()
endforeach()
if(functions EQUAL 0)
  message(FATAL_ERROR "${CTAGS} found no function in ${count} files: is it universal-ctags?")
endif()
if(long)
  list(JOIN long "\n  " named)
  message(FATAL_ERROR "functions over ${MAX_LINES} lines (split them into named phases):\n  ${named}")
endif()
message(STATUS "${functions} functions in ${count} C++ files, none over ${MAX_LINES} lines outside data tables")
