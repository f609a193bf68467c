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
    # Line tables for the reports (-g1), full debug information only in a Debug build: -g took
    # 37 % longer to compile under the sanitizers than -g1 and wrote 4× the object size.
    target_compile_options(${target} PRIVATE -fsanitize=${_san} -fno-omit-frame-pointer
                                             $<IF:$<CONFIG:Debug>,-g,-g1>)
    target_link_options(${target} PUBLIC -fsanitize=${_san})
    target_compile_definitions(${target} PUBLIC FRICTOPT_ENABLE_ASSERTS=1)
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

# frictopt_add_test(module SOURCES x_test.cpp ... [LABELS slow] [DEPENDS extra])
# One test binary per call, registered with CTest through gtest_discover_tests.
function(frictopt_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;LABELS;DEFINITIONS" ${ARGN})
  if("slow" IN_LIST ARG_LABELS AND NOT FRICTOPT_BUILD_SLOW_TESTS)
    return()
  endif()
  add_executable(${name}_test ${ARG_SOURCES})
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
  set(_labels ${ARG_LABELS})
  if(NOT _labels)
    set(_labels quick)
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
