# physlab_add_lab(): one call adds a stage (lab) with its two implementations, tests, demo and
# benchmark. Layout of stage NN_name:
#   labs/NN_name/*.cpp          student implementation -> library physlab_NN_name_labs
#   solutions/NN_name/*.cpp     reference              -> library physlab_NN_name_ref
#   common/src/NN_name/*.cpp    framework code of the stage, compiled into both
#   tests/NN_name, tests/hidden/NN_name   graded tests -> test_NN_name (ref), test_NN_name_labs
#   demos/NN_name, bench/NN_name          -> demo_NN_name(_labs), bench_NN_name
# Isolation: a stage's libraries link the *reference* of every earlier stage (when solutions/
# is present), so a student's bug in lab 1 costs no points in lab 3.

set(PHYSLAB_ROOT "${CMAKE_CURRENT_LIST_DIR}/..")
get_filename_component(PHYSLAB_ROOT "${PHYSLAB_ROOT}" ABSOLUTE)
set(PHYSLAB_HAVE_SOLUTIONS OFF)
if(EXISTS "${PHYSLAB_ROOT}/solutions")
  set(PHYSLAB_HAVE_SOLUTIONS ON)
endif()
set_property(GLOBAL PROPERTY PHYSLAB_STAGES "")

function(physlab_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(PHYSLAB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

function(physlab_add_common)
  file(GLOB sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/src/*.cpp")
  add_library(physlab_common STATIC ${sources})
  target_include_directories(physlab_common PUBLIC "${PHYSLAB_ROOT}/common/include")
  target_include_directories(physlab_common SYSTEM PRIVATE "${GNUPLOT_IOSTREAM_INCLUDE_DIR}")
  target_link_libraries(physlab_common PUBLIC Eigen3::Eigen PRIVATE Boost::iostreams Boost::filesystem)
  physlab_warnings(physlab_common)

  # One precompiled header (Catch2 + Eigen) shared by every test object library.
  add_library(physlab_test_pch OBJECT "${PHYSLAB_ROOT}/tests/support/pch.cpp")
  target_link_libraries(physlab_test_pch PUBLIC physlab_common Catch2::Catch2)
  physlab_warnings(physlab_test_pch)
  target_precompile_headers(physlab_test_pch PUBLIC
      <catch2/catch.hpp> <Eigen/Dense> <Eigen/Sparse> <random> <vector> <string>)

  # Test support (seeded random inputs, helpers) and Catch2's main, compiled once.
  file(GLOB support CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/support/*.cpp")
  list(FILTER support EXCLUDE REGEX "pch\\.cpp$")
  add_library(physlab_test_support STATIC ${support})
  target_include_directories(physlab_test_support PUBLIC "${PHYSLAB_ROOT}/tests/support")
  target_link_libraries(physlab_test_support PUBLIC physlab_common Catch2::Catch2WithMain)
  target_precompile_headers(physlab_test_support REUSE_FROM physlab_test_pch)
  physlab_warnings(physlab_test_support)

endfunction()

# Framework tests (tagged [common]): they grade nothing. They check validation in common/ and
# Lab 1's framework half, so they link the reference of Lab 1.
function(physlab_add_framework_tests)
  file(GLOB common_tests CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/common/*.cpp")
  add_executable(test_common ${common_tests})
  target_link_libraries(test_common PRIVATE physlab_test_support physlab_01_particles_ref)
  target_precompile_headers(test_common REUSE_FROM physlab_test_pch)
  physlab_warnings(test_common)
  catch_discover_tests(test_common TEST_PREFIX "common: " PROPERTIES TIMEOUT 60 LABELS solutions)
endfunction()

# Build the executables `name` (reference) and `name_labs` (student) from the same objects.
function(physlab_variant_executables name stage objects)
  # Helpers (ARGN) come first: they call into the lab, and static libraries resolve left to right.
  add_executable(${name} $<TARGET_OBJECTS:${objects}>)
  target_link_libraries(${name} PRIVATE ${ARGN} physlab_${stage}_ref)
  if(TARGET physlab_${stage}_labs)
    add_executable(${name}_labs $<TARGET_OBJECTS:${objects}>)
    target_link_libraries(${name}_labs PRIVATE ${ARGN} physlab_${stage}_labs)
  endif()
endfunction()

function(physlab_add_lab stage)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  set(deps "")
  foreach(dep IN LISTS ARG_DEPENDS)
    list(APPEND deps physlab_${dep}_ref)
  endforeach()
  file(GLOB framework CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/src/${stage}/*.cpp")

  # Student implementation, from PHYSLAB_LABS_DIR (absent in a submission that left it out).
  file(GLOB lab_sources CONFIGURE_DEPENDS "${PHYSLAB_LABS_DIR}/${stage}/*.cpp")
  if(lab_sources)
    add_library(physlab_${stage}_labs STATIC ${lab_sources} ${framework})
    target_link_libraries(physlab_${stage}_labs PUBLIC physlab_common ${deps})
    physlab_warnings(physlab_${stage}_labs)
  endif()

  # Reference implementation; in the published student version it is the student's own.
  if(PHYSLAB_HAVE_SOLUTIONS)
    file(GLOB ref_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/solutions/${stage}/*.cpp")
  else()
    file(GLOB ref_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/labs/${stage}/*.cpp")
  endif()
  add_library(physlab_${stage}_ref STATIC ${ref_sources} ${framework})
  target_link_libraries(physlab_${stage}_ref PUBLIC physlab_common ${deps})
  physlab_warnings(physlab_${stage}_ref)

  # Graded tests: compiled once, linked against each implementation.
  file(GLOB tests CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/${stage}/*.cpp")
  if(PHYSLAB_HIDDEN_TESTS)
    file(GLOB hidden CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/hidden/${stage}/*.cpp")
    list(APPEND tests ${hidden})
  endif()
  add_library(physlab_${stage}_tests OBJECT ${tests})
  target_link_libraries(physlab_${stage}_tests PRIVATE physlab_test_support)
  target_precompile_headers(physlab_${stage}_tests REUSE_FROM physlab_test_pch)
  physlab_warnings(physlab_${stage}_tests)
  physlab_variant_executables(test_${stage} ${stage} physlab_${stage}_tests physlab_test_support)
  catch_discover_tests(test_${stage} TEST_PREFIX "${stage}: " PROPERTIES TIMEOUT 120 LABELS solutions)
  if(TARGET test_${stage}_labs)
    catch_discover_tests(test_${stage}_labs TEST_PREFIX "labs ${stage}: "
                         PROPERTIES TIMEOUT 120 LABELS labs)
  endif()

  # Demo (charts) for both implementations, benchmark for the reference.
  file(GLOB demo_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/demos/${stage}/*.cpp")
  if(demo_sources)
    add_library(physlab_${stage}_demo OBJECT ${demo_sources})
    target_link_libraries(physlab_${stage}_demo PRIVATE physlab_common)
    physlab_warnings(physlab_${stage}_demo)
    physlab_variant_executables(demo_${stage} ${stage} physlab_${stage}_demo)
  endif()
  file(GLOB bench_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/bench/${stage}/*.cpp")
  if(bench_sources)
    add_executable(bench_${stage} ${bench_sources})
    target_link_libraries(bench_${stage} PRIVATE physlab_${stage}_ref)
    physlab_warnings(bench_${stage})
    # Optional peer engines (Bullet, MuJoCo, Boost.Odeint, ...): cmake/peers/NN_name.cmake may
    # link them into the benchmark when installed; nothing else ever needs them.
    set(PHYSLAB_BENCH_TARGET bench_${stage})
    include("${PHYSLAB_ROOT}/cmake/peers/${stage}.cmake" OPTIONAL)
  endif()
  set_property(GLOBAL APPEND PROPERTY PHYSLAB_STAGES ${stage})
endfunction()
