# One precompiled header of the heavy third-party and standard headers, built once and reused by
# every static library, object library and executable of the project (REUSE_FROM), for LOCBENCH_PCH builds.
# Every target gets the same header-only dependencies and fmt, so that each compiles with the
# flags and definitions the header was made with. The C++17 ROS 1 unit is marked
# SKIP_PRECOMPILE_HEADERS (datasets/io). docs/decisions.md: "One precompiled header for make build".
set(LOCBENCH_PCH_HEADERS
    <algorithm> <cmath> <functional> <map> <memory> <optional> <string> <variant> <vector>
    <Eigen/Core> <Eigen/Dense> <nlohmann/json.hpp> <fmt/format.h>)
set(LOCBENCH_PCH_DEPENDENCIES locbench_options Eigen3::Eigen fmt::fmt nlohmann_json::nlohmann_json Boost::boost)

file(WRITE ${PROJECT_BINARY_DIR}/locbench_pch_anchor.cpp "// The unit that builds the precompiled header.\n")
add_library(locbench_pch STATIC ${PROJECT_BINARY_DIR}/locbench_pch_anchor.cpp)
target_link_libraries(locbench_pch PUBLIC ${LOCBENCH_PCH_DEPENDENCIES})
target_precompile_headers(locbench_pch PRIVATE ${LOCBENCH_PCH_HEADERS})

# locbench_reuse_pch(DIR): every static library, object library and executable defined in DIR and below.
function(locbench_reuse_pch dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    if(type MATCHES "^(STATIC_LIBRARY|OBJECT_LIBRARY|EXECUTABLE)$" AND NOT t STREQUAL "locbench_pch")
      target_link_libraries(${t} PRIVATE ${LOCBENCH_PCH_DEPENDENCIES})
      target_precompile_headers(${t} REUSE_FROM locbench_pch)
    endif()
  endforeach()
  get_property(subdirectories DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(s ${subdirectories})
    locbench_reuse_pch(${s})
  endforeach()
endfunction()
locbench_reuse_pch(${PROJECT_SOURCE_DIR})
