# CTest "geometry:simd-objects": the objects of one instruction set's kernels
# (geometry/simd/*.cpp compiled with -mavx2, or -mavx512f) define no weak function that does
# not name that instruction set. The linker keeps one copy of each inline function or
# template instance; a copy compiled with -mavx512f of anything the rest of the program also
# calls (an Eigen accessor, a std:: helper) could be the one kept, and fault on a CPU without
# AVX-512 (geometry/simd.h).
# cmake -DNM=nm -DARCH=avx2 "-DOBJECTS=a.o|b.o" -P cmake/check_simd_objects.cmake
string(REPLACE "|" ";" objects "${OBJECTS}")
set(bad "")
set(count 0)
foreach(o IN LISTS objects)
  execute_process(COMMAND ${NM} -C --defined-only ${o} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${o}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[0-9a-fA-F]+ W (.*)$")
      math(EXPR count "${count} + 1")
      if(NOT CMAKE_MATCH_1 MATCHES "xsimd::${ARCH}")
        string(APPEND bad "  ${CMAKE_MATCH_1}\n")
      endif()
    endif()
  endforeach()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "no weak function at all in the ${ARCH} objects: are they the kernels?")
endif()
if(bad)
  message(FATAL_ERROR "weak functions compiled for ${ARCH} that other code may share:\n${bad}")
endif()
message("${count} weak functions in the ${ARCH} kernels, each specific to ${ARCH}")
