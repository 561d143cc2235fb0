# Shows cmake/check_module_deps.cmake failing on purpose (ctest module_deps_fixtures):
#   cmake -DCHECKER=cmake/check_module_deps.cmake -DWORK_DIR=<build>/module_deps_fixtures -P cmake/test_module_deps.cmake
# Builds a small source tree under WORK_DIR (modules core, geometry, features,
# optimize, map) and runs the checker on three module tables:
# 1. as declared (map DEPS features; features DEPS geometry): passes, so an
#    include through the closure (map -> geometry) is allowed;
# 2. the same tree plus map/fuse.cpp including optimize/ at line 3: fails,
#    naming the file, the line and the fix;
# 3. a table where geometry also depends on map: fails on the cycle.
cmake_minimum_required(VERSION 3.22)

file(REMOVE_RECURSE ${WORK_DIR})
set(src ${WORK_DIR}/src/stillslam)
file(WRITE ${src}/core/error.h "#pragma once\n")
file(WRITE ${src}/geometry/se3.h "#pragma once\n#include \"stillslam/core/error.h\"\n")
file(WRITE ${src}/features/orb.h "#pragma once\n#include \"stillslam/geometry/se3.h\"\n")
file(WRITE ${src}/optimize/ba.h "#pragma once\n#include \"stillslam/geometry/se3.h\"\n")
file(WRITE ${src}/map/map.h "#pragma once\n\n#include \"stillslam/features/orb.h\"\n#include \"stillslam/geometry/se3.h\"\n")

function(write_table name)
  set(text "set(STILLSLAM_MODULES core geometry features optimize map)\n")
  foreach(entry ${ARGN})
    string(REPLACE ":" ";" parts ${entry})
    list(POP_FRONT parts module)
    string(APPEND text "set(STILLSLAM_MODULE_DEPS_${module} \"${parts}\")\n")
  endforeach()
  file(WRITE ${WORK_DIR}/${name}.cmake "${text}")
endfunction()
write_table(declared geometry:core features:geometry optimize:geometry map:features)
write_table(cycle geometry:core:map features:geometry optimize:geometry map:features)

function(run_check table out_result out_text)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${WORK_DIR} -DMODULE_TABLE=${WORK_DIR}/${table}.cmake
                          -P ${CHECKER}
                  RESULT_VARIABLE result OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  set(${out_result} ${result} PARENT_SCOPE)
  set(${out_text} "${stdout}${stderr}" PARENT_SCOPE)
endfunction()

function(expect_text text expected)
  string(FIND "${text}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected the checker to print\n  ${expected}\nbut it printed\n${text}")
  endif()
endfunction()

# 1. A consistent tree passes.
run_check(declared result text)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the consistent fixture tree should pass, the checker printed\n${text}")
endif()
expect_text("${text}" "module boundaries: 5 modules, includes match the declared DEPS, no cycle")

# 2. map/fuse.cpp includes optimize/, which map does not declare.
file(WRITE ${src}/map/fuse.cpp "#include \"stillslam/map/map.h\"\n\n#include \"stillslam/optimize/ba.h\"\n")
run_check(declared result text)
if(result EQUAL 0)
  message(FATAL_ERROR "the checker passed a tree where map includes optimize/ undeclared:\n${text}")
endif()
expect_text("${text}" "src/stillslam/map/fuse.cpp:3 includes optimize/ but map declares only features (and through them core, geometry); add it to map's DEPS in CMakeLists.txt or remove the include")
expect_text("${text}" "module boundaries: 1 problem(s)")

# 3. geometry -> map -> features -> geometry is a cycle.
file(REMOVE ${src}/map/fuse.cpp)
run_check(cycle result text)
if(result EQUAL 0)
  message(FATAL_ERROR "the checker passed a table with a dependency cycle:\n${text}")
endif()
expect_text("${text}" "dependency cycle: geometry -> map -> features -> geometry; remove one of these DEPS in CMakeLists.txt")
message(STATUS "module_deps_fixtures: the checker passes the consistent tree and fails on the undeclared include and on the cycle")
