# stillslam_module(name DEPS ... [TEST_DEPS ...]): a static library from src/stillslam/<name>/*.cpp,
# or an interface library when the module is header-only so far.
set(STILLSLAM_MODULES "")
function(stillslam_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS" ${ARGN})
  set(STILLSLAM_TEST_DEPS_${name} ${ARG_TEST_DEPS} PARENT_SCOPE)
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

# One GoogleTest executable per module that has tests: test_<module>.
function(stillslam_module_tests)
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
