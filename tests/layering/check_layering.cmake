# The floors of the tree, checked on every `make test`: a file under FOLDER may include only
# headers from the folders listed for it (README "Layout"). tests/ may include anything.
# Run: cmake -DSRC=<root> -P this file.
set(rules
  # floor 0
  "core:core"
  # floor 1: on core only
  "reports:core|reports"
  "datasets/io:core|datasets/io"
  "datasets/sim:core|datasets/sim"
  "algorithms:core|algorithms"
  # floor 2
  "datasets/catalog:core|datasets/io|datasets/catalog"
  "datasets/diagnosis:core|datasets/sim|datasets/diagnosis"
  "baselines:core|algorithms|baselines"
  "experiment_framework:core|reports|experiment_framework"
  # floor 3: pipelines join methods and data
  "pipelines:core|reports|algorithms|baselines|datasets|experiment_framework|pipelines"
  # floor 4: experiments, speed kernels, fuzz targets and the CLI
  "benchmarks/experiments:core|reports|algorithms|baselines|datasets|experiment_framework|pipelines|benchmarks/experiments"
  "benchmarks/speed:core|reports|algorithms|baselines|datasets|experiment_framework|pipelines|benchmarks/speed"
  "fuzz:core|reports|algorithms|baselines|datasets|pipelines|experiment_framework|fuzz"
  "cli:core|reports|algorithms|baselines|datasets|pipelines|experiment_framework|cli"
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
