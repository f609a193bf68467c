# SPDX-License-Identifier: MIT
# Runs PROGRAM (with ARGS, a ;-list) under the dynamic linker's binding trace with every symbol
# bound at load time (LD_BIND_NOW=1, LD_DEBUG=bindings) and checks that each BLAS/LAPACK routine
# CHOLMOD's supernodal factorization calls is bound to an OpenBLAS library file, not to ATLAS'
# libf77blas/libatlas or the reference libblas (docs/benchmarks.md, "Which BLAS").
#   cmake -DPROGRAM=<exe> [-DARGS=a;b] -P check_blas_bindings.cmake
if(NOT PROGRAM)
  message(FATAL_ERROR "check_blas_bindings.cmake: give -DPROGRAM=<executable>")
endif()
set(ENV{LD_BIND_NOW} 1)
set(ENV{LD_DEBUG} bindings)
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE trace)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} ${ARGS} exited ${rc}:\n${out}")
endif()
set(failures "")
set(checked 0)
foreach(symbol dgemm_ dsyrk_ dtrsm_ dpotrf_)
  string(REGEX MATCHALL "binding file [^\n]*libcholmod[^\n]* to [^\n]*: normal symbol `${symbol}'" lines "${trace}")
  if(NOT lines)
    string(APPEND failures "  no binding of CHOLMOD's ${symbol} in the trace (is CHOLMOD loaded?)\n")
  endif()
  foreach(line IN LISTS lines)
    math(EXPR checked "${checked} + 1")
    string(REGEX REPLACE ".* to ([^ ]+) .*" "\\1" target "${line}")
    file(REAL_PATH "${target}" target)  # through Debian's alternatives links
    if(NOT target MATCHES "openblas")
      string(APPEND failures "  CHOLMOD's ${symbol} is bound to ${target}\n")
    endif()
  endforeach()
endforeach()
if(failures)
  message(FATAL_ERROR "BLAS bindings of ${PROGRAM} ${ARGS}: not OpenBLAS\n${failures}")
endif()
message(STATUS "${checked} CHOLMOD BLAS/LAPACK bindings of ${PROGRAM}, all to OpenBLAS")
