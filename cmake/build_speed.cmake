# Fresh-build speed (issue #5: the README's demo must finish in under 5 minutes
# on a fresh 2-core machine, build included).
#
# - Precompiled header: the standard, Eigen, OpenCV, spdlog and nlohmann/json
#   headers nearly every file includes are parsed once, into the PCH of the
#   stillslam_pch object library, and every module library and the stillslam
#   binary reuse that one PCH (REUSE_FROM; GCC accepts it because they all
#   compile with the same flags and definitions, -Winvalid-pch + -Werror would
#   stop the build otherwise). Ceres/glog and CLI11 stay out: few files need
#   them, and glog's macros should not leak into every file. Tests and
#   benchmarks do not use it: with the PCH, GCC 12 reports a false
#   -Warray-bounds inside <string> (char_traits.h) for
#   tests/segmentation/class_filter_test.cpp that it keeps quiet about without
#   it (system-header warnings are not suppressed through the PCH). Should a
#   library file ever hit the same, build with -DSTILLSLAM_PCH=OFF to confirm
#   and tell the build owner.
# - Unity builds: each module library and the stillslam binary compile as
#   combined translation units of up to STILLSLAM_UNITY_BATCH files, so the
#   headers and the inline code they instantiate (Eigen, json, CLI11, ...)
#   are compiled once per batch instead of once per file. Tests and
#   benchmarks stay one file per translation unit, as before.
#
# Both are on by default so every build dir compiles the same way (a name
# clash between two files of a module shows up for its owner first);
# -DSTILLSLAM_PCH=OFF -DSTILLSLAM_UNITY_BUILD=OFF gives the plain
# one-file-per-TU build (e.g. to check that every file includes what it uses).
option(STILLSLAM_PCH "Precompile the common third-party headers once for the libraries and the binary" ON)
option(STILLSLAM_UNITY_BUILD "Compile each module as combined translation units" ON)
set(STILLSLAM_UNITY_BATCH 8 CACHE STRING "Source files per unity translation unit")
# Files compiled on their own because a file-local name clashes with another
# file of the same module inside a unity TU. Renaming the clashing name (the
# module owner's call) lets the file join its module's batches again.
set(STILLSLAM_UNITY_EXCLUDE)

if(CCACHE_PROGRAM AND STILLSLAM_PCH)
  # ccache can cache compilations that use a GCC precompiled header only with
  # these sloppiness settings (ccache manual, "Precompiled headers").
  set(CMAKE_CXX_COMPILER_LAUNCHER
      ${CMAKE_COMMAND} -E env
      "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime"
      ${CCACHE_PROGRAM})
endif()

if(STILLSLAM_PCH)
  set(STILLSLAM_PCH_SOURCE ${CMAKE_BINARY_DIR}/stillslam_pch.cpp)
  if(NOT EXISTS ${STILLSLAM_PCH_SOURCE})
    file(WRITE ${STILLSLAM_PCH_SOURCE} "// The target that owns the shared precompiled header (cmake/build_speed.cmake).\n")
  endif()
  add_library(stillslam_pch OBJECT ${STILLSLAM_PCH_SOURCE})
  # The same usage requirements as stillslam_core, so the definitions match.
  target_link_libraries(stillslam_pch PUBLIC Eigen3::Eigen ${OpenCV_LIBS} spdlog::spdlog nlohmann_json::nlohmann_json
                                             Threads::Threads)
  target_compile_options(stillslam_pch PRIVATE ${STILLSLAM_WARNINGS})
  target_precompile_headers(stillslam_pch PRIVATE
    <algorithm> <array> <atomic> <chrono> <cmath> <cstddef> <cstdint> <filesystem> <fstream> <functional>
    <iostream> <limits> <map> <memory> <mutex> <optional> <set> <sstream> <string> <unordered_map>
    <unordered_set> <utility> <vector>
    <Eigen/Core> <Eigen/Geometry>
    <opencv2/core.hpp> <opencv2/imgproc.hpp>
    <spdlog/spdlog.h>
    <nlohmann/json.hpp>)
endif()

# stillslam_speed_up(target [UNITY] [BATCH n]): reuse the shared PCH; UNITY also
# turns on the unity build for the target, in batches of BATCH files (default
# STILLSLAM_UNITY_BATCH). Used for the module libraries and the binary.
function(stillslam_speed_up target)
  cmake_parse_arguments(ARG "UNITY" "BATCH" "" ${ARGN})
  if(NOT ARG_BATCH)
    set(ARG_BATCH ${STILLSLAM_UNITY_BATCH})
  endif()
  if(STILLSLAM_PCH)
    target_precompile_headers(${target} REUSE_FROM stillslam_pch)
  endif()
  if(STILLSLAM_UNITY_BUILD AND ARG_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${ARG_BATCH})
    get_target_property(sources ${target} SOURCES)
    foreach(file ${STILLSLAM_UNITY_EXCLUDE})
      if(${PROJECT_SOURCE_DIR}/${file} IN_LIST sources)
        set_source_files_properties(${PROJECT_SOURCE_DIR}/${file} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
      endif()
    endforeach()
  endif()
endfunction()
