# physlab_add_lab(): one call adds a stage (lab) with its two implementations, tests, demo and
# benchmark. Layout of stage NN_name:
#   labs/NN_name/*.cpp          student implementation -> library physlab_NN_name_labs
#   solutions/NN_name/*.cpp     reference              -> library physlab_NN_name_ref
#   common/src/NN_name/*.cpp    framework code of the stage, compiled into both
#   tests/NN_name, tests/hidden/NN_name   graded tests -> test_NN_name (ref), test_NN_name_labs
#   demos/NN_name, bench/NN_name          -> demo_NN_name(_labs), bench_NN_name
#   views/NN_name                         -> view_NN_name(_labs): scenes for ./physlab view
# Isolation: a stage's libraries link the *reference* of every earlier stage (when solutions/
# is present), so a student's bug in lab 1 costs no points in lab 3. A published student copy has
# no solutions/: there a stage's "reference" library is the reference source of a lab the
# instructor has released (`./physlab publish --release`, released/NN_name/*.cpp), else the
# student's own labs/NN_name. Later stages link it either way. PHYSLAB_RELEASED=OFF links the
# student's own earlier labs even where the lab is released. No reference ships compiled: a
# library of an unreleased lab would answer that lab's tests for the student (an oracle). Nor does
# framework code that computes what a student function computes (common/answers/NN_name/): it
# ships with the lab's release, and stand-ins built on the student's functions take its place
# until then (physlab_add_lab()).

set(PHYSLAB_ROOT "${CMAKE_CURRENT_LIST_DIR}/..")
get_filename_component(PHYSLAB_ROOT "${PHYSLAB_ROOT}" ABSOLUTE)
set(PHYSLAB_HAVE_SOLUTIONS OFF)
if(EXISTS "${PHYSLAB_ROOT}/solutions")
  set(PHYSLAB_HAVE_SOLUTIONS ON)
endif()
set_property(GLOBAL PROPERTY PHYSLAB_STAGES "")
option(PHYSLAB_RELEASED "Link later labs against the released reference of earlier labs (released/, student copies)" ON)
# Checked at every build (CONFIGURE_DEPENDS): a pull that brings a newly released lab reconfigures,
# so that later labs build on it from then on.
file(GLOB PHYSLAB_RELEASED_LABS CONFIGURE_DEPENDS LIST_DIRECTORIES true "${PHYSLAB_ROOT}/released/*")
list(FILTER PHYSLAB_RELEASED_LABS INCLUDE REGEX "/[0-9][0-9]_[a-z0-9_]+$")  # the labs, not released/README.txt
if(PHYSLAB_RELEASED_LABS AND PHYSLAB_RELEASED AND NOT PHYSLAB_HAVE_SOLUTIONS)
  list(TRANSFORM PHYSLAB_RELEASED_LABS REPLACE ".*/" "")
  message(STATUS "later labs build on the released reference of: ${PHYSLAB_RELEASED_LABS}")
endif()

# Remote grading needs Linux (fork, pipes, a static worker) and the grader's sandbox.
set(PHYSLAB_REMOTE OFF)
if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND PHYSLAB_HAVE_SOLUTIONS AND NOT PHYSLAB_PORTABLE_RUNNER)
  set(PHYSLAB_REMOTE ON)
endif()
find_package(Python3 COMPONENTS Interpreter)

option(PHYSLAB_FRAMEWORK_ANSWERS "Compile the framework answers (common/answers/), not their stand-ins (common/unreleased/); instructor's tree only" ON)

option(PHYSLAB_PORTABLE_RUNNER "Test runner without the grader's notary (automatic where executables are not ELF: macOS, Windows)" OFF)

if(MSVC)
  set(PHYSLAB_WARNING_FLAGS /W4 /permissive-)
else()
  set(PHYSLAB_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow)
endif()

function(physlab_warnings target)
  target_compile_options(${target} PRIVATE ${PHYSLAB_WARNING_FLAGS})
  if(PHYSLAB_WERROR AND MSVC)
    target_compile_options(${target} PRIVATE /WX)
  elseif(PHYSLAB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Warnings, and the precompiled Eigen headers of physlab_pch: what every library, demo and
# benchmark file is compiled with.
function(physlab_cxx target)
  physlab_warnings(${target})
  target_precompile_headers(${target} REUSE_FROM physlab_pch)
endfunction()

function(physlab_add_common)
  # Eigen's Core and Geometry, precompiled once: physlab/math.hpp includes them, so every PhysLab
  # file does, and parsing them is most of a small file's compile time. Exactly what math.hpp
  # includes and nothing more, so that a file missing an #include still fails here as it would in
  # the grader (which compiles submissions without it).
  add_library(physlab_pch OBJECT "${PHYSLAB_ROOT}/common/src/pch/pch.cpp")
  target_link_libraries(physlab_pch PUBLIC Eigen3::Eigen)
  physlab_warnings(physlab_pch)  # -Wpedantic changes predefined macros: the users' flags exactly
  target_precompile_headers(physlab_pch PUBLIC <Eigen/Core> <Eigen/Geometry>)

  file(GLOB sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/src/*.cpp")
  add_library(physlab_common STATIC ${sources})
  target_include_directories(physlab_common PUBLIC "${PHYSLAB_ROOT}/common/include")
  # Nothing but Eigen and the standard library: the charts (plot.cpp) pipe their scripts to
  # gnuplot through the C library, so whatever links the framework (every test executable, the
  # grader's links) builds with libc++ as well as libstdc++.
  target_link_libraries(physlab_common PUBLIC Eigen3::Eigen)
  physlab_cxx(physlab_common)

  # One precompiled header (Catch2 + Eigen) shared by every test object library.
  add_library(physlab_test_pch OBJECT "${PHYSLAB_ROOT}/tests/support/pch.cpp")
  target_link_libraries(physlab_test_pch PUBLIC physlab_common Catch2::Catch2)
  physlab_warnings(physlab_test_pch)
  target_precompile_headers(physlab_test_pch PUBLIC
      <catch2/catch.hpp> <Eigen/Dense> <Eigen/Sparse> <random> <vector> <string>)

  # Test support (seeded random inputs, oracles) and the test main, compiled once. The main
  # (runner.cpp) compiles Catch2's implementation, so it cannot use the precompiled header.
  file(GLOB support CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/support/*.cpp")
  list(FILTER support EXCLUDE REGEX "(pch|runner)\\.cpp$")
  add_library(physlab_test_support OBJECT ${support})
  target_include_directories(physlab_test_support PUBLIC "${PHYSLAB_ROOT}/tests/support")
  target_link_libraries(physlab_test_support PUBLIC physlab_common Catch2::Catch2)
  target_precompile_headers(physlab_test_support REUSE_FROM physlab_test_pch)
  physlab_warnings(physlab_test_support)
  add_library(physlab_test_runner OBJECT "${PHYSLAB_ROOT}/tests/support/runner.cpp")
  target_link_libraries(physlab_test_runner PRIVATE Catch2::Catch2)
  physlab_warnings(physlab_test_runner)
  # Catch2's implementation: -O1 compiles it in 20 s instead of 29 (it is on the path to every
  # test executable) and runs the assertions as fast for the tests' purposes.
  target_compile_options(physlab_test_runner PRIVATE $<IF:$<CXX_COMPILER_ID:MSVC>,/O1,-O1>)
  # The wire between a checker and its worker (physlab_add_remote), Linux only.
  set(worker_filter "")
  if(PHYSLAB_REMOTE)
    add_library(physlab_remote OBJECT "${PHYSLAB_ROOT}/tests/support/remote/remote.cpp"
                                      "${PHYSLAB_ROOT}/tests/support/remote/handles.cpp")
    target_include_directories(physlab_remote PUBLIC "${PHYSLAB_ROOT}/tests/support")
    target_link_libraries(physlab_remote PUBLIC physlab_common)
    physlab_cxx(physlab_remote)
    # A worker per test case in every checker (listener.cpp); objects, so that the linker keeps it.
    add_library(physlab_remote_listener OBJECT "${PHYSLAB_ROOT}/tests/support/remote/listener.cpp")
    target_link_libraries(physlab_remote_listener PRIVATE physlab_remote Catch2::Catch2)
    physlab_warnings(physlab_remote_listener)
    # The worker's seccomp filter, written once per build (tests/support/remote/filter.cpp).
    find_path(PHYSLAB_SECCOMP_INCLUDE_DIR seccomp.h)
    find_library(PHYSLAB_SECCOMP_LIBRARY seccomp)
    if(NOT PHYSLAB_SECCOMP_INCLUDE_DIR OR NOT PHYSLAB_SECCOMP_LIBRARY)
      physlab_missing("libseccomp (the grader's sandbox of submitted code)" libseccomp-dev)
    endif()
    add_executable(physlab_worker_filter "${PHYSLAB_ROOT}/tests/support/remote/filter.cpp")
    target_include_directories(physlab_worker_filter SYSTEM PRIVATE "${PHYSLAB_SECCOMP_INCLUDE_DIR}")
    target_link_libraries(physlab_worker_filter PRIVATE "${PHYSLAB_SECCOMP_LIBRARY}")
    physlab_warnings(physlab_worker_filter)
    add_custom_command(OUTPUT "${CMAKE_BINARY_DIR}/grading/worker.bpf"
                       COMMAND physlab_worker_filter "${CMAKE_BINARY_DIR}/grading/worker.bpf"
                       DEPENDS physlab_worker_filter COMMENT "The grading worker's seccomp filter")
    add_custom_target(physlab_worker_bpf ALL DEPENDS "${CMAKE_BINARY_DIR}/grading/worker.bpf")
    set(worker_filter "${CMAKE_BINARY_DIR}/grading/worker.bpf")
    # A worker is linked statically (its sandbox holds no file but itself): nothing beyond the
    # C++ runtime.
    set(PHYSLAB_WORKER_LIBRARIES -pthread
        CACHE INTERNAL "what a grading worker links besides the labs and the framework")
  endif()
  # The grader's notary forks in .preinit_array: ELF executables only. Elsewhere, or on request
  # (CI checks that path on Linux), the runner is the portable one (see runner.cpp), and
  # toolchain.json says so: the grader refuses to grade with it.
  set(notary true)
  if(PHYSLAB_PORTABLE_RUNNER OR NOT CMAKE_EXECUTABLE_FORMAT STREQUAL "ELF")
    set(notary false)
    target_compile_definitions(physlab_test_runner PRIVATE PHYSLAB_PORTABLE_RUNNER)
  endif()

  # What the grader needs to compile a submission apart from this tree and link it with the
  # instructor's objects (tools/grader/kit.py reads it; see the Grading page).
  string(TOUPPER "${CMAKE_BUILD_TYPE}" build_type)
  list(JOIN PHYSLAB_WARNING_FLAGS " " warnings)
  file(GENERATE OUTPUT "${CMAKE_BINARY_DIR}/grading/toolchain.json" CONTENT "{
  \"compiler\": \"${CMAKE_CXX_COMPILER}\",
  \"notary\": ${notary},
  \"worker_filter\": \"${worker_filter}\",
  \"flags\": \"${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${build_type}} ${CMAKE_CXX17_STANDARD_COMPILE_OPTION}\",
  \"warnings\": \"${warnings}\",
  \"include\": \"${PHYSLAB_ROOT}/common/include\",
  \"system_include\": [\"$<JOIN:$<TARGET_PROPERTY:Eigen3::Eigen,INTERFACE_INCLUDE_DIRECTORIES>,\",\">\"],
  \"main\": [\"$<JOIN:$<TARGET_OBJECTS:physlab_test_runner>;$<TARGET_OBJECTS:physlab_test_support>,\",\">\"],
  \"common\": \"$<TARGET_FILE:physlab_common>\",
  \"worker_libraries\": [\"$<JOIN:${PHYSLAB_WORKER_LIBRARIES},\",\">\"],
  \"libraries\": [\"-pthread\"]
}
")
endfunction()

# A test object library compiles as one file (a unity build): Catch2's and Eigen's templates are
# then instantiated once per suite rather than once per file, which takes a quarter to a half off
# a suite's compile time. So the files of one suite (visible, hidden) share one namespace: two of
# them must not define the same helper name, not even in anonymous namespaces.
function(physlab_test_unity objects)
  target_precompile_headers(${objects} REUSE_FROM physlab_test_pch)
  set_target_properties(${objects} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
endfunction()

# Framework tests (tagged [common]): they grade nothing. They check validation in common/ and
# Lab 1's framework half, so they link the reference of Lab 1.
function(physlab_add_framework_tests)
  file(GLOB common_tests CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/common/*.cpp")
  if(NOT PHYSLAB_REMOTE)  # the wire of remote grading (test_remote.cpp) is built only where it is used
    list(FILTER common_tests EXCLUDE REGEX "test_remote\\.cpp$")
  endif()
  add_executable(test_common ${common_tests})
  target_link_libraries(test_common PRIVATE physlab_test_runner physlab_test_support physlab_01_particles_ref)
  if(PHYSLAB_REMOTE)
    # Lab 2's codecs build spring systems and workspaces (state.hpp): its framework, with its reference.
    target_link_libraries(test_common PRIVATE physlab_remote physlab_02_springs_ref)
    # The wire's test sends Lab 4's shapes, whose constructors are Lab 4's framework
    target_link_libraries(test_common PRIVATE physlab_04_collision_ref)
    # The worker of test_remote.cpp's calls that cross processes and nest.
    add_executable(physlab_test_worker "${PHYSLAB_ROOT}/tests/support/remote/test_worker.cpp")
    target_link_libraries(physlab_test_worker PRIVATE physlab_remote physlab_01_particles_ref)
    physlab_cxx(physlab_test_worker)
    add_dependencies(test_common physlab_test_worker)
    target_compile_definitions(test_common PRIVATE PHYSLAB_TEST_WORKER="$<TARGET_FILE:physlab_test_worker>")
  endif()
  physlab_test_unity(test_common)
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

# Graded tests of `stage` from `sources` into the object library `objects` and the executables
# `exe` (reference), `exe_labs` (labs/) and `exe_labs_<file>` for each file in `mixes` (that
# student file with the reference of the others).
function(physlab_add_tests stage objects exe sources mixes)
  add_library(${objects} OBJECT ${sources})
  target_link_libraries(${objects} PRIVATE physlab_test_support)
  physlab_test_unity(${objects})
  physlab_warnings(${objects})
  physlab_variant_executables(${exe} ${stage} ${objects} physlab_test_runner physlab_test_support)
  foreach(unit IN LISTS mixes)
    add_executable(${exe}_labs_${unit} $<TARGET_OBJECTS:${objects}>)
    target_link_libraries(${exe}_labs_${unit} PRIVATE physlab_test_runner physlab_test_support
                          physlab_${stage}_mix_${unit})
  endforeach()
endfunction()

# One object library per source file (`prefix`_<file name without .cpp>), so that a file can be
# linked without the others; `out` gets the file names.
function(physlab_unit_objects prefix sources deps out)
  set(units "")
  foreach(source IN LISTS sources)
    get_filename_component(unit "${source}" NAME_WE)
    add_library(${prefix}_${unit} OBJECT "${source}")
    target_link_libraries(${prefix}_${unit} PUBLIC physlab_common ${deps})
    physlab_cxx(${prefix}_${unit})
    list(APPEND units ${unit})
  endforeach()
  set(${out} "${units}" PARENT_SCOPE)
endfunction()

# Adds the objects of the files `units` (made by physlab_unit_objects with `prefix`) to `target`.
function(physlab_add_units target prefix units)
  foreach(unit IN LISTS units)
    target_sources(${target} PRIVATE $<TARGET_OBJECTS:${prefix}_${unit}>)
  endforeach()
endfunction()

# Grading where no submitted code runs in the process that decides (docs/grading.md, "Where
# submitted code runs"), for a lab added with REMOTE: tools/remote_gen.py writes, from the lab's
# stubs, a proxy of each student function and the worker's table. check_NN (check_NN_hidden) is
# the lab's tests linked with the proxies and no implementation of the lab: the grader runs it
# as it runs a test executable, and it starts the worker, which the grader links from the
# submitted objects and the server's (`server` in grading/NN.json), statically, so that its
# sandbox needs no file but itself. worker_NN is that link with the reference: the checker and
# worker pair on the reference passes every test (./physlab test checks it).
function(physlab_add_remote stage framework_objects in_worker deps dep_files hidden out)
  set(generated "${CMAKE_BINARY_DIR}/remote/${stage}")
  file(GLOB stubs CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/labs/${stage}/*.cpp")
  add_custom_command(
      OUTPUT "${generated}_proxy.cpp" "${generated}_server.cpp"
      COMMAND "${Python3_EXECUTABLE}" "${PHYSLAB_ROOT}/tools/remote_gen.py" "${PHYSLAB_ROOT}/labs/${stage}"
              "${generated}_proxy.cpp" "${generated}_server.cpp" ${in_worker}
      DEPENDS ${stubs} ${in_worker} "${PHYSLAB_ROOT}/tools/remote_gen.py"
      COMMENT "Proxies and worker table of ${stage}")
  # The framework of the stage and the reference of earlier ones, without this stage's own
  # functions: in the checker the proxies stand in for them.
  add_library(physlab_${stage}_checked STATIC ${framework_objects} "${generated}_proxy.cpp")
  target_link_libraries(physlab_${stage}_checked PUBLIC physlab_common physlab_remote ${deps})
  physlab_cxx(physlab_${stage}_checked)
  add_executable(check_${stage} $<TARGET_OBJECTS:physlab_${stage}_tests> $<TARGET_OBJECTS:physlab_remote_listener>)
  target_link_libraries(check_${stage} PRIVATE physlab_test_runner physlab_test_support physlab_${stage}_checked)
  set(hidden_checker "")
  if(hidden)
    add_executable(check_${stage}_hidden $<TARGET_OBJECTS:physlab_${stage}_hidden>
                   $<TARGET_OBJECTS:physlab_remote_listener>)
    target_link_libraries(check_${stage}_hidden PRIVATE physlab_test_runner physlab_test_support
                          physlab_${stage}_checked)
    set(hidden_checker "$<TARGET_FILE:check_${stage}_hidden>")
  endif()
  add_library(physlab_${stage}_server OBJECT "${generated}_server.cpp")
  target_link_libraries(physlab_${stage}_server PRIVATE physlab_common physlab_remote)
  physlab_cxx(physlab_${stage}_server)
  # Linked as the grader links a submission's worker: archives by file, static libraries only.
  add_executable(worker_${stage} $<TARGET_OBJECTS:physlab_${stage}_server> $<TARGET_OBJECTS:physlab_remote>)
  add_dependencies(worker_${stage} physlab_${stage}_ref physlab_common)
  target_link_libraries(worker_${stage} PRIVATE -static -Wl,--start-group $<TARGET_FILE:physlab_${stage}_ref>
                        ${dep_files} $<TARGET_FILE:physlab_common> -Wl,--end-group ${PHYSLAB_WORKER_LIBRARIES})
  set(${out} "
  \"checker\": \"$<TARGET_FILE:check_${stage}>\",
  \"checker_hidden\": \"${hidden_checker}\",
  \"server\": [\"$<JOIN:$<TARGET_OBJECTS:physlab_${stage}_server>;$<TARGET_OBJECTS:physlab_remote>,\",\">\"],
  \"reference_worker\": \"$<TARGET_FILE:worker_${stage}>\"," PARENT_SCOPE)
endfunction()

function(physlab_add_lab stage)
  cmake_parse_arguments(ARG "REMOTE" "" "DEPENDS;IN_WORKER" ${ARGN})
  # Earlier stages this one links, with their own dependencies (the grader links them whole).
  set(closure "")
  foreach(dep IN LISTS ARG_DEPENDS)
    get_property(dep_closure GLOBAL PROPERTY PHYSLAB_DEPENDS_${dep})
    list(APPEND closure ${dep_closure} ${dep})
  endforeach()
  list(REMOVE_DUPLICATES closure)
  set_property(GLOBAL PROPERTY PHYSLAB_DEPENDS_${stage} ${closure})
  set(deps "")
  foreach(dep IN LISTS ARG_DEPENDS)
    list(APPEND deps physlab_${dep}_ref)
  endforeach()

  # Framework code of the stage, compiled once and shared by both implementations.
  file(GLOB framework CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/src/${stage}/*.cpp")
  # Framework answers: framework code that computes what a student function of the stage computes
  # (the matrix-free cone PGS of Lab 6 is solveLcpPgsCone()'s sweeps over per-body velocities), in
  # common/answers/NN_name/. They ship as a released lab's reference does: the instructor's tree
  # compiles them; a student's copy has them once the lab is released
  # (released/NN_name/framework/, ./physlab publish --release) and until then compiles their
  # stand-ins, common/unreleased/NN_name/, one file of the same name each, built on the student's
  # own functions. PHYSLAB_FRAMEWORK_ANSWERS=OFF compiles the stand-ins in the instructor's tree
  # too, to test them against the reference.
  file(GLOB answers CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/answers/${stage}/*.cpp")
  file(GLOB stand_ins CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/common/unreleased/${stage}/*.cpp")
  if(PHYSLAB_HAVE_SOLUTIONS)
    set(answer_names "${answers}")
    set(stand_in_names "${stand_ins}")
    list(TRANSFORM answer_names REPLACE ".*/" "")
    list(TRANSFORM stand_in_names REPLACE ".*/" "")
    if(NOT answer_names STREQUAL stand_in_names)
      message(FATAL_ERROR "lab ${stage}: common/answers/${stage} holds '${answer_names}' and "
                          "common/unreleased/${stage} '${stand_in_names}': each framework answer needs "
                          "its stand-in of the same name")
    endif()
  endif()
  if(PHYSLAB_HAVE_SOLUTIONS AND PHYSLAB_FRAMEWORK_ANSWERS)
    list(APPEND framework ${answers})
  elseif(NOT PHYSLAB_HAVE_SOLUTIONS AND PHYSLAB_RELEASED AND EXISTS "${PHYSLAB_ROOT}/released/${stage}/framework")
    file(GLOB released_answers CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/released/${stage}/framework/*.cpp")
    list(APPEND framework ${released_answers})
  else()
    list(APPEND framework ${stand_ins})
  endif()
  # IN_WORKER: framework files that a remote lab's checker leaves to the worker (see
  # physlab_add_remote); every other build links them as the rest of the framework.
  set(in_worker "")
  foreach(file IN LISTS ARG_IN_WORKER)
    list(APPEND in_worker "${PHYSLAB_ROOT}/common/src/${stage}/${file}")
  endforeach()
  set(framework_objects "")
  set(checked_framework_objects "")
  if(in_worker)
    list(REMOVE_ITEM framework ${in_worker})
    add_library(physlab_${stage}_in_worker OBJECT ${in_worker})
    target_link_libraries(physlab_${stage}_in_worker PUBLIC physlab_common ${deps})
    physlab_cxx(physlab_${stage}_in_worker)
    set(framework_objects $<TARGET_OBJECTS:physlab_${stage}_in_worker>)
  endif()
  if(framework)
    add_library(physlab_${stage}_framework OBJECT ${framework})
    target_link_libraries(physlab_${stage}_framework PUBLIC physlab_common ${deps})
    physlab_cxx(physlab_${stage}_framework)
    list(APPEND framework_objects $<TARGET_OBJECTS:physlab_${stage}_framework>)
    set(checked_framework_objects $<TARGET_OBJECTS:physlab_${stage}_framework>)
  endif()

  # Student implementation, from PHYSLAB_LABS_DIR (absent in a submission that left it out).
  file(GLOB lab_sources CONFIGURE_DEPENDS "${PHYSLAB_LABS_DIR}/${stage}/*.cpp")
  if(lab_sources)
    physlab_unit_objects(physlab_${stage}_labs "${lab_sources}" "${deps}" lab_units)
    add_library(physlab_${stage}_labs STATIC ${framework_objects})
    physlab_add_units(physlab_${stage}_labs physlab_${stage}_labs "${lab_units}")
    target_link_libraries(physlab_${stage}_labs PUBLIC physlab_common ${deps})
  endif()

  # Reference implementation; in the published student version the released reference source of
  # the lab, or the student's own where the lab is not released.
  if(PHYSLAB_HAVE_SOLUTIONS)
    file(GLOB ref_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/solutions/${stage}/*.cpp")
  elseif(PHYSLAB_RELEASED AND EXISTS "${PHYSLAB_ROOT}/released/${stage}")
    file(GLOB ref_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/released/${stage}/*.cpp")
  else()
    file(GLOB ref_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/labs/${stage}/*.cpp")
  endif()
  physlab_unit_objects(physlab_${stage}_ref "${ref_sources}" "${deps}" ref_units)
  add_library(physlab_${stage}_ref STATIC ${framework_objects})
  physlab_add_units(physlab_${stage}_ref physlab_${stage}_ref "${ref_units}")
  target_link_libraries(physlab_${stage}_ref PUBLIC physlab_common ${deps})
  set_property(GLOBAL APPEND PROPERTY PHYSLAB_STAGES ${stage})
  # A lab left out of a course's student copy that a lab of the course builds on (./physlab
  # publish --course): its released reference only, no tests, demo, scene or benchmark.
  file(GLOB tests CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/${stage}/*.cpp")
  if(NOT tests AND NOT lab_sources)
    return()
  endif()

  # Partial credit: a test grades the functions of its handout sections ([sec=N] tags), so with
  # the reference at hand each student file also gets a library of its own beside the reference of
  # the lab's other files (physlab_NN_mix_<file>), linked into test_NN_labs_<file>; ./physlab test
  # runs each test in the executable of the files its sections are in (tools/grader/tree.py).
  set(mixes "")
  if(PHYSLAB_HAVE_SOLUTIONS AND lab_sources)
    foreach(unit IN LISTS lab_units)
      list(FIND ref_units "${unit}" found)
      if(found LESS 0)
        continue()
      endif()
      set(others "${ref_units}")
      list(REMOVE_ITEM others "${unit}")
      add_library(physlab_${stage}_mix_${unit} STATIC ${framework_objects})
      physlab_add_units(physlab_${stage}_mix_${unit} physlab_${stage}_ref "${others}")
      physlab_add_units(physlab_${stage}_mix_${unit} physlab_${stage}_labs "${unit}")
      target_link_libraries(physlab_${stage}_mix_${unit} PUBLIC physlab_common ${deps})
      list(APPEND mixes ${unit})
    endforeach()
  endif()

  # Graded tests: compiled once, linked against each implementation. Hidden tests get their own
  # executables, so that their text is never in a process that runs the visible tests.
  physlab_add_tests(${stage} physlab_${stage}_tests test_${stage} "${tests}" "${mixes}")
  catch_discover_tests(test_${stage} TEST_PREFIX "${stage}: " PROPERTIES TIMEOUT 120 LABELS solutions)
  if(TARGET test_${stage}_labs)
    catch_discover_tests(test_${stage}_labs TEST_PREFIX "labs ${stage}: "
                         PROPERTIES TIMEOUT 120 LABELS labs)
  endif()
  set(hidden "")
  if(PHYSLAB_HIDDEN_TESTS)
    file(GLOB hidden CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/tests/hidden/${stage}/*.cpp")
  endif()
  set(hidden_objects "")
  if(hidden)
    physlab_add_tests(${stage} physlab_${stage}_hidden test_${stage}_hidden "${hidden}" "${mixes}")
    catch_discover_tests(test_${stage}_hidden TEST_PREFIX "${stage} hidden: " PROPERTIES TIMEOUT 120 LABELS solutions)
    set(hidden_objects $<TARGET_OBJECTS:physlab_${stage}_hidden>)
  endif()

  # The instructor's side of a graded link: tests, framework objects, earlier stages' reference,
  # and the reference's object of each file of this stage (partial credit: see above).
  set(reference_units "")
  if(PHYSLAB_HAVE_SOLUTIONS)
    foreach(unit IN LISTS ref_units)
      if(reference_units)
        string(APPEND reference_units ", ")
      endif()
      string(APPEND reference_units "\"${unit}\": \"$<TARGET_OBJECTS:physlab_${stage}_ref_${unit}>\"")
    endforeach()
  endif()
  set(dep_files "")
  foreach(dep IN LISTS closure)
    list(APPEND dep_files $<TARGET_FILE:physlab_${dep}_ref>)
  endforeach()
  set(remote_json "")
  if(ARG_REMOTE AND PHYSLAB_HAVE_SOLUTIONS AND PHYSLAB_REMOTE)
    physlab_add_remote(${stage} "${checked_framework_objects}" "${in_worker}" "${deps}" "${dep_files}" "${hidden}"
                       remote_json)
  endif()
  file(GENERATE OUTPUT "${CMAKE_BINARY_DIR}/grading/${stage}.json" CONTENT "{
  \"stage\": \"${stage}\",${remote_json}
  \"tests\": [\"$<JOIN:$<TARGET_OBJECTS:physlab_${stage}_tests>,\",\">\"],
  \"hidden\": [$<$<BOOL:${hidden}>:\"$<JOIN:${hidden_objects},\",\">\">],
  \"framework\": [$<$<BOOL:${framework}>:\"$<JOIN:${framework_objects},\",\">\">],
  \"depends\": [$<$<BOOL:${closure}>:\"$<JOIN:${dep_files},\",\">\">],
  \"reference\": {${reference_units}}
}
")

  # Demo (charts) and the 3-D viewer's scene recorder (./physlab view NN) for both
  # implementations, from demos/ and views/; benchmark for the reference.
  foreach(program IN ITEMS demo view)
    file(GLOB program_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/${program}s/${stage}/*.cpp")
    if(program_sources)
      add_library(physlab_${stage}_${program} OBJECT ${program_sources})
      target_link_libraries(physlab_${stage}_${program} PRIVATE physlab_common)
      physlab_cxx(physlab_${stage}_${program})
      physlab_variant_executables(${program}_${stage} ${stage} physlab_${stage}_${program})
    endif()
  endforeach()
  file(GLOB bench_sources CONFIGURE_DEPENDS "${PHYSLAB_ROOT}/bench/${stage}/*.cpp")
  if(bench_sources)
    add_executable(bench_${stage} ${bench_sources})
    target_link_libraries(bench_${stage} PRIVATE physlab_${stage}_ref)
    physlab_cxx(bench_${stage})
    # Optional peer engines (Bullet, MuJoCo, Boost.Odeint, ...): cmake/peers/NN_name.cmake may
    # link them into the benchmark when installed; nothing else ever needs them.
    set(PHYSLAB_BENCH_TARGET bench_${stage})
    include("${PHYSLAB_ROOT}/cmake/peers/${stage}.cmake" OPTIONAL)
  endif()
endfunction()
