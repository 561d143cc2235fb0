# stillslam_module(name DEPS ... [TEST_DEPS ...]): a static library from src/stillslam/<name>/*.cpp,
# or an interface library when the module is header-only so far.
# The stillslam_<m> entries of DEPS are also the module's declared
# dependencies: cmake/check_module_deps.cmake (ctest module_deps) fails when a
# file of the module includes a module outside their transitive closure.
set(STILLSLAM_MODULES "")
set(STILLSLAM_MODULE_TABLE ${CMAKE_BINARY_DIR}/stillslam_modules.cmake)
function(stillslam_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS" ${ARGN})
  set(STILLSLAM_TEST_DEPS_${name} ${ARG_TEST_DEPS} PARENT_SCOPE)
  set(module_deps ${ARG_DEPS})
  list(FILTER module_deps INCLUDE REGEX "^stillslam_")
  list(TRANSFORM module_deps REPLACE "^stillslam_" "")
  set_property(GLOBAL APPEND_STRING PROPERTY STILLSLAM_MODULE_TABLE_TEXT
               "list(APPEND STILLSLAM_MODULES ${name})\nset(STILLSLAM_MODULE_DEPS_${name} \"${module_deps}\")\n")
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/stillslam/${name}/*.cpp)
  set(target stillslam_${name})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    target_compile_options(${target} PRIVATE ${STILLSLAM_WARNINGS})
    stillslam_speed_up(${target} UNITY)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  set(STILLSLAM_MODULES ${STILLSLAM_MODULES} ${name} PARENT_SCOPE)
endfunction()

# The module table for the boundary check, written once every stillslam_module()
# line of the top-level CMakeLists.txt has run.
function(stillslam_write_module_table)
  get_property(text GLOBAL PROPERTY STILLSLAM_MODULE_TABLE_TEXT)
  file(CONFIGURE OUTPUT ${STILLSLAM_MODULE_TABLE} CONTENT
       "# Generated from the stillslam_module() lines of CMakeLists.txt.\nset(STILLSLAM_MODULES \"\")\n${text}" @ONLY)
endfunction()
cmake_language(DEFER CALL stillslam_write_module_table)

# ctest module_deps: the include graph of src/ matches the declared DEPS.
# ctest module_deps_fixtures: the same check fails, with the expected
# messages, on small trees with an undeclared include and with a cycle.
function(stillslam_module_dep_tests)
  add_test(NAME module_deps
           COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DMODULE_TABLE=${STILLSLAM_MODULE_TABLE}
                   -P ${PROJECT_SOURCE_DIR}/cmake/check_module_deps.cmake)
  add_test(NAME module_deps_fixtures
           COMMAND ${CMAKE_COMMAND} -DCHECKER=${PROJECT_SOURCE_DIR}/cmake/check_module_deps.cmake
                   -DWORK_DIR=${CMAKE_BINARY_DIR}/module_deps_fixtures
                   -P ${PROJECT_SOURCE_DIR}/cmake/test_module_deps.cmake)
endfunction()

# One GoogleTest executable per module that has tests: test_<module>.
function(stillslam_module_tests)
  stillslam_module_dep_tests()
  foreach(name ${STILLSLAM_MODULES})
    file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/${name}/*.cpp)
    if(sources)
      add_executable(test_${name} ${sources})
      target_link_libraries(test_${name} PRIVATE stillslam_${name} ${STILLSLAM_TEST_DEPS_${name}} GTest::gtest GTest::gtest_main)
      target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
      target_compile_definitions(test_${name} PRIVATE
        STILLSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
        STILLSLAM_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared"
        STILLSLAM_BINARY="${CMAKE_BINARY_DIR}/stillslam")
      target_compile_options(test_${name} PRIVATE ${STILLSLAM_WARNINGS})
      set_target_properties(test_${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
      gtest_discover_tests(test_${name} DISCOVERY_MODE PRE_TEST
        WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTIES TIMEOUT 600)
    endif()
  endforeach()
endfunction()
