# SPDX-License-Identifier: MIT
include(GNUInstallDirs)

# One helper per kind of target, so each module's CMake is a few lines and the layering of
# docs/architecture.md §1 (a module links only modules above it) is a link-time fact.

# OpenBLAS (FRICTOPT_OPENBLAS_LIBRARY) as the first DT_NEEDED entry of an executable or module,
# ahead of every library the link line names (link options precede the objects and libraries):
# the dynamic linker then binds every BLAS/LAPACK symbol of the process or of the module's
# dependencies (CHOLMOD's, LAPACK's, Ceres') to OpenBLAS, whatever ATLAS a dependency also
# needs. --no-as-needed keeps the entry although the target itself may call no BLAS routine.
function(frictopt_link_openblas_first target)
  get_target_property(type ${target} TYPE)
  if(FRICTOPT_OPENBLAS_LIBRARY AND type MATCHES "^(EXECUTABLE|MODULE_LIBRARY|SHARED_LIBRARY)$")
    target_link_options(${target} BEFORE PRIVATE "LINKER:--push-state,--no-as-needed"
                        "${FRICTOPT_OPENBLAS_LIBRARY}" "LINKER:--pop-state")
  endif()
endfunction()

# Flags every frictopt target gets: C++20, warnings, sanitizers, the portable -march, and for
# executables and modules OpenBLAS first (above).
function(frictopt_target_defaults target)
  frictopt_link_openblas_first(${target})
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           $<$<CONFIG:Release>:-O2 -march=x86-64-v2>)
  if(FRICTOPT_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(FRICTOPT_SANITIZE)
    if("address" IN_LIST FRICTOPT_SANITIZE AND "thread" IN_LIST FRICTOPT_SANITIZE)
      message(FATAL_ERROR "FRICTOPT_SANITIZE='${FRICTOPT_SANITIZE}': address and thread "
                          "sanitizers cannot be combined; choose one.")
    endif()
    list(JOIN FRICTOPT_SANITIZE "," _san)
    # A test program's own code is instrumented only with FRICTOPT_SANITIZE_TEST_CODE (below).
    get_target_property(_is_test_code ${target} FRICTOPT_TEST_CODE)
    if(FRICTOPT_SANITIZE_TEST_CODE OR NOT _is_test_code)
      # Line tables for the reports (-g1), full debug information only in a Debug build: -g took
      # 37 % longer to compile under the sanitizers than -g1 and wrote 4× the object size.
      target_compile_options(${target} PRIVATE -fsanitize=${_san} -fno-omit-frame-pointer
                                               $<IF:$<CONFIG:Debug>,-g,-g1>)
    endif()
    target_link_options(${target} PUBLIC -fsanitize=${_san})
    target_compile_definitions(${target} PUBLIC FRICTOPT_ENABLE_ASSERTS=1)
    # For code (the tests) that must know it runs under AddressSanitizer, also when it is not
    # instrumented itself and so has no __SANITIZE_ADDRESS__.
    if("address" IN_LIST FRICTOPT_SANITIZE)
      target_compile_definitions(${target} PUBLIC FRICTOPT_ADDRESS_SANITIZER=1)
    endif()
  endif()
endfunction()

# frictopt_add_module(name SOURCES a.cpp b.cpp DEPENDS frictopt::x LIBS third::party)
# creates frictopt_<name> with alias frictopt::<name>.
function(frictopt_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;LIBS;PRIVATE_LIBS" ${ARGN})
  if(ARG_SOURCES)
    add_library(frictopt_${name} STATIC ${ARG_SOURCES})
    target_include_directories(frictopt_${name}
                               PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
                               PRIVATE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(frictopt_${name} PUBLIC ${ARG_DEPENDS} ${ARG_LIBS}
                          PRIVATE ${ARG_PRIVATE_LIBS})
    frictopt_target_defaults(frictopt_${name})
  else()
    add_library(frictopt_${name} INTERFACE)
    target_include_directories(frictopt_${name} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                          $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(frictopt_${name} INTERFACE ${ARG_DEPENDS} ${ARG_LIBS})
  endif()
  # Installed and imported as frictopt::<name>, the same name as the alias used in the build.
  set_target_properties(frictopt_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(frictopt::${name} ALIAS frictopt_${name})
  set_property(GLOBAL APPEND PROPERTY FRICTOPT_MODULES ${name})
endfunction()

# frictopt_add_test(module SOURCES x_test.cpp ... [LABELS slow|end_to_end] [DEPENDS extra]
#                   [DEFINITIONS X=1 ...] [COMMAND_LINE])
# One test binary per call, registered with CTest through gtest_discover_tests. Labels: none means
# quick; end_to_end (whole studies, or the command line run on whole cases) is also quick.
# COMMAND_LINE: the program runs the frictopt binary (FRICTOPT_BINARY, FRICTOPT_SOURCE_DIR, built
# first). A program left out by FRICTOPT_BUILD_SLOW_TESTS / _END_TO_END_TESTS has no target.
function(frictopt_add_test name)
  cmake_parse_arguments(ARG "COMMAND_LINE" "" "SOURCES;DEPENDS;LABELS;DEFINITIONS" ${ARGN})
  if("slow" IN_LIST ARG_LABELS AND NOT FRICTOPT_BUILD_SLOW_TESTS)
    return()
  endif()
  if("end_to_end" IN_LIST ARG_LABELS AND NOT FRICTOPT_BUILD_END_TO_END_TESTS)
    return()
  endif()
  add_executable(${name}_test ${ARG_SOURCES})
  set_target_properties(${name}_test PROPERTIES FRICTOPT_TEST_CODE ON)
  target_include_directories(${name}_test PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_link_libraries(${name}_test PRIVATE ${ARG_DEPENDS} GTest::gtest GTest::gtest_main)
  frictopt_target_defaults(${name}_test)
  # The test programs' own code at -O1 (after the -O2 above, so it wins): the library under test
  # keeps the Release -O2; a test's body is checks and calls into it, and -O1 compiles it in
  # about two thirds of the time (measured on tests/contact/tresca_solver_test.cpp: 35 s → 23 s).
  target_compile_options(${name}_test PRIVATE $<$<CONFIG:Release>:-O1>)
  if(ARG_DEFINITIONS)
    target_compile_definitions(${name}_test PRIVATE ${ARG_DEFINITIONS})
  endif()
  if(ARG_COMMAND_LINE)
    target_compile_definitions(${name}_test PRIVATE FRICTOPT_BINARY="$<TARGET_FILE:frictopt>"
                                                    FRICTOPT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    add_dependencies(${name}_test frictopt)
  endif()
  if(FRICTOPT_SANITIZE AND FRICTOPT_SANITIZE_TEST_CODE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12 warns "may be used uninitialized" inside libstdc++'s <regex> when the sanitizers
    # instrument it (GCC PR 105562, a false positive in std::__detail::_NFA); tests use <regex>.
    target_compile_options(${name}_test PRIVATE -Wno-maybe-uninitialized)
  endif()
  set(_labels ${ARG_LABELS})
  if(NOT _labels)
    set(_labels quick)
  elseif(_labels STREQUAL "end_to_end")
    set(_labels quick end_to_end)
  endif()
  gtest_discover_tests(${name}_test PROPERTIES LABELS "${_labels}" DISCOVERY_TIMEOUT 60
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()

# frictopt_add_benchmark(name SOURCES x.cpp DEPENDS frictopt::fem)
function(frictopt_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} benchmark::benchmark)
  # bench/common/*.hpp: the shared timing helpers and test bodies of the benchmarks.
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/bench)
  frictopt_target_defaults(${name})
endfunction()
