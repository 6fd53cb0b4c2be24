# The project's C++ sources below SRC, relative to it, in `files`: every .cpp and .h of the code's
# folders and of the top level. Included by the style checks that read C++.
set(folders algorithms baselines benchmarks cli core datasets examples fuzz pipelines reports tests)
set(files)
foreach(folder IN LISTS folders)
  file(GLOB_RECURSE found LIST_DIRECTORIES false RELATIVE ${SRC} ${SRC}/${folder}/*.cpp ${SRC}/${folder}/*.h)
  list(APPEND files ${found})
endforeach()
file(GLOB loose LIST_DIRECTORIES false RELATIVE ${SRC} ${SRC}/*.cpp ${SRC}/*.h)
list(APPEND files ${loose})
