# The floors of the tree, checked on every `make test`: a file under FOLDER may include only
# headers from the folders listed for it (README "Layout"). Run: cmake -DSRC=<root> -P this file.
set(rules
  "core:core"
  "algorithms:core|algorithms"
  "baselines:core|algorithms|baselines"
  "datasets/io:core|datasets/io"
  "datasets/catalog:core|datasets/io|datasets/catalog|algorithms"
  "datasets/sim:core|datasets/sim"
  "reports:core|reports"
)
set(violations "")
foreach(rule IN LISTS rules)
  string(REPLACE ":" ";" parts "${rule}")
  list(GET parts 0 folder)
  list(GET parts 1 allowed)
  file(GLOB_RECURSE files "${SRC}/${folder}/*.h" "${SRC}/${folder}/*.cpp")
  foreach(f IN LISTS files)
    file(STRINGS "${f}" includes REGEX "^#include \"")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
      if(NOT header MATCHES "^(${allowed})/" AND header MATCHES "/")
        file(RELATIVE_PATH rel "${SRC}" "${f}")
        list(APPEND violations "${rel} includes ${header} (${folder}/ may include only ${allowed})")
      endif()
    endforeach()
  endforeach()
endforeach()
if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layering: includes against the floors:\n  ${text}")
endif()
message(STATUS "layering: every include follows the floors")
