# Copies next to the shared object BINARY every shared library it loads (as ldd lists them,
# directly or not) outside the C and C++ runtimes, under its SONAME: the folder then runs on
# a machine with only those runtimes. BINARY finds the copies, and they find each other,
# through BINARY's RPATH $ORIGIN (DT_RPATH, which the loader also searches for the
# libraries' own dependencies).
#   cmake -DBINARY=path/to/binary.so -P bundle_libraries.cmake
get_filename_component(folder "${BINARY}" DIRECTORY)
execute_process(COMMAND ldd "${BINARY}" OUTPUT_VARIABLE listing RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "ldd ${BINARY} failed")
endif()
# glibc's libraries and the C++ runtime are the machine's own.
set(runtime "^(ld-linux-x86-64|libc|libm|libdl|libpthread|librt|libresolv|libutil|libstdc\\+\\+|libgcc_s)\\.so")
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  if(line MATCHES "not found")
    message(FATAL_ERROR "${BINARY}: ${line}")
  endif()
  if(NOT line MATCHES "^[ \t]*([^ \t]+) => (/[^ \t]+)")
    continue()
  endif()
  set(name "${CMAKE_MATCH_1}")
  set(path "${CMAKE_MATCH_2}")
  if(name MATCHES "${runtime}" OR path STREQUAL "${folder}/${name}")
    continue()
  endif()
  get_filename_component(real "${path}" REALPATH)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E copy_if_different "${real}" "${folder}/${name}"
                  RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "cannot copy ${real} to ${folder}")
  endif()
endforeach()
