# The tire as a component (docs/coupling.md): the shared library libtirefe.so with the C
# API of include/tirefe.h, and the install rules: executables, library, header, Lua
# modules, tire property files, a CMake package and a pkg-config file.
include(CMakePackageConfigHelpers)

add_library(tirefe_shared SHARED $<TARGET_OBJECTS:tirefe_objects>)
target_link_libraries(tirefe_shared PRIVATE ${TIREFE_DEPENDENCIES})
target_include_directories(tirefe_shared INTERFACE
  $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
set_target_properties(tirefe_shared PROPERTIES
  OUTPUT_NAME tirefe VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
  EXPORT_NAME tirefe)
add_library(tirefe::tirefe ALIAS tirefe_shared)

# The C example host of docs/coupling.md: a quarter car dropped onto the tire.
add_executable(quarter_car_drop examples/quarter_car_drop.c)
target_link_libraries(quarter_car_drop PRIVATE tirefe::tirefe m)
# Its C++ twin of docs/spindle.md, over the internal spindle exchange.
add_executable(spindle_host examples/spindle_host.cpp)
target_link_libraries(spindle_host PRIVATE tirefe_lib)

install(TARGETS tirefe RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET tirefe-mpi)
  install(TARGETS tirefe-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(TARGETS tirefe_shared EXPORT tirefeTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES include/tirefe.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY lua/ DESTINATION ${TIREFE_INSTALL_LUA_DIR} FILES_MATCHING PATTERN "*.lua")
install(DIRECTORY inputs/tires/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tirefe/tires FILES_MATCHING PATTERN "*.tir")
install(FILES examples/quarter_car_drop.c DESTINATION ${CMAKE_INSTALL_DATADIR}/tirefe/examples)

set(TIREFE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/tirefe)
install(EXPORT tirefeTargets NAMESPACE tirefe:: DESTINATION ${TIREFE_CMAKE_DIR})
file(WRITE ${CMAKE_BINARY_DIR}/package/tirefeConfig.cmake
  "# find_package(tirefe): the imported target tirefe::tirefe (libtirefe.so and tirefe.h).\n"
  "include(\"\${CMAKE_CURRENT_LIST_DIR}/tirefeTargets.cmake\")\n")
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/tirefeConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/tirefeConfig.cmake ${CMAKE_BINARY_DIR}/package/tirefeConfigVersion.cmake
  DESTINATION ${TIREFE_CMAKE_DIR})

# pkg-config: the prefix is taken from the .pc file's own place, so a moved prefix works.
file(RELATIVE_PATH TIREFE_PC_TO_PREFIX ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" TIREFE_PC_TO_PREFIX "${TIREFE_PC_TO_PREFIX}")
file(WRITE ${CMAKE_BINARY_DIR}/package/tirefe.pc
  "prefix=\${pcfiledir}/${TIREFE_PC_TO_PREFIX}\n"
  "libdir=\${prefix}/${CMAKE_INSTALL_LIBDIR}\n"
  "includedir=\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}\n"
  "luadir=\${prefix}/${TIREFE_INSTALL_LUA_DIR}\n\n"
  "Name: tirefe\n"
  "Description: 2D finite-element tire behind its spindle (C API)\n"
  "Version: ${PROJECT_VERSION}\n"
  "Libs: -L\${libdir} -ltirefe\n"
  "Cflags: -I\${includedir}\n")
install(FILES ${CMAKE_BINARY_DIR}/package/tirefe.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)


# tirefe_tire.fmu: the tire as an FMI 2.0 co-simulation FMU (docs/fmu.md), self-
# contained: the model description; binaries/linux64/ with the binary (the library's
# objects, SuiteSparse linked in statically, and the FMI functions, nothing else exported)
# and a copy of every other shared library it loads outside the C and C++ runtimes (Lua,
# HDF5 and theirs; Debian's static Lua and HDF5 are not position-independent), found
# through its RPATH $ORIGIN; resources/ with the tire property file, road files and the
# Lua modules. Its GUID follows the version and the model description.
file(SHA1 ${CMAKE_SOURCE_DIR}/cmake/modelDescription.xml.in TIREFE_FMU_DESCRIPTION_HASH)
string(UUID TIREFE_FMU_GUID NAMESPACE 6ba7b811-9dad-11d1-80b4-00c04fd430c8
       NAME "tirefe_tire ${PROJECT_VERSION} ${TIREFE_FMU_DESCRIPTION_HASH}" TYPE SHA1)
set(TIREFE_FMU_GUID "{${TIREFE_FMU_GUID}}")
set(TIREFE_FMU_DIR ${CMAKE_BINARY_DIR}/fmu/tirefe_tire)
configure_file(cmake/modelDescription.xml.in ${TIREFE_FMU_DIR}/modelDescription.xml @ONLY)
set(TIREFE_FMU_STATIC_LIBRARIES)
foreach(name klu amd colamd btf suitesparseconfig)  # in link order
  find_library(TIREFE_STATIC_${name} lib${name}.a REQUIRED)
  list(APPEND TIREFE_FMU_STATIC_LIBRARIES ${TIREFE_STATIC_${name}})
endforeach()
add_library(tirefe_fmu MODULE src/fmu/tirefe_fmu.cpp src/fmu/fmu_files.cpp $<TARGET_OBJECTS:tirefe_objects>)
target_include_directories(tirefe_fmu PRIVATE src include)
target_compile_definitions(tirefe_fmu PRIVATE TIREFE_FMU_GUID="${TIREFE_FMU_GUID}")
target_link_libraries(tirefe_fmu PRIVATE Eigen3::Eigen PkgConfig::LUA PkgConfig::HDF5 ${TIREFE_FMU_STATIC_LIBRARIES}
  Threads::Threads ${CMAKE_DL_LIBS})
# Only the fmi2 functions are the FMU's interface: no C++ symbol may clash with a host's.
target_link_options(tirefe_fmu PRIVATE -Wl,--exclude-libs,ALL -Wl,--as-needed -Wl,--disable-new-dtags
  -Wl,--version-script=${CMAKE_SOURCE_DIR}/src/fmu/fmi2_exports.map)
set_target_properties(tirefe_fmu PROPERTIES OUTPUT_NAME tirefe_tire PREFIX ""
  LIBRARY_OUTPUT_DIRECTORY ${TIREFE_FMU_DIR}/binaries/linux64
  BUILD_WITH_INSTALL_RPATH ON INSTALL_RPATH "$ORIGIN")
add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/tirefe_tire.fmu
  COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:tirefe_fmu> -P ${CMAKE_SOURCE_DIR}/cmake/bundle_libraries.cmake
  COMMAND ${CMAKE_COMMAND} -E copy_directory ${CMAKE_SOURCE_DIR}/lua ${TIREFE_FMU_DIR}/resources/lua
  COMMAND ${CMAKE_COMMAND} -E copy_directory ${CMAKE_SOURCE_DIR}/inputs/roads ${TIREFE_FMU_DIR}/resources/roads
  COMMAND ${CMAKE_COMMAND} -E copy ${CMAKE_SOURCE_DIR}/inputs/tires/145SR12.tir ${TIREFE_FMU_DIR}/resources/145SR12.tir
  COMMAND ${CMAKE_COMMAND} -E tar cf ${CMAKE_BINARY_DIR}/tirefe_tire.fmu --format=zip
          modelDescription.xml binaries resources
  WORKING_DIRECTORY ${TIREFE_FMU_DIR}
  DEPENDS tirefe_fmu ${TIREFE_FMU_DIR}/modelDescription.xml ${CMAKE_SOURCE_DIR}/inputs/tires/145SR12.tir
          ${CMAKE_SOURCE_DIR}/cmake/bundle_libraries.cmake
  COMMENT "Packing tirefe_tire.fmu")
add_custom_target(tirefe_tire_fmu ALL DEPENDS ${CMAKE_BINARY_DIR}/tirefe_tire.fmu)
install(FILES ${CMAKE_BINARY_DIR}/tirefe_tire.fmu DESTINATION ${CMAKE_INSTALL_DATADIR}/tirefe)

# The Python package `import tirefe` (pybind11 over libtirefe.so, Debian's pybind11-dev;
# built when pybind11 is found): tirefe/ with its compiled part _core, its Python part and
# type stubs (src/python/tirefe), and the distribution's metadata (numpy required). It is
# installed where Debian's python3 looks for a prefix's packages,
# <prefix>/lib/python3.X/dist-packages (for /usr/local and /usr alike), and finds the
# library from there. In the build tree it is build/python/tirefe.
if(NOT PYTHON_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(PYTHON_EXECUTABLE /usr/bin/python3)  # Debian's, with numpy (the Python tests name it too)
endif()
find_package(pybind11 2.6 CONFIG QUIET)
if(pybind11_FOUND)
  execute_process(COMMAND ${PYTHON_EXECUTABLE} -c "import sys; print('%d.%d' % sys.version_info[:2])"
    OUTPUT_VARIABLE TIREFE_PYTHON_MINOR OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(TIREFE_INSTALL_PYTHON_DIR lib/python${TIREFE_PYTHON_MINOR}/dist-packages)
  # PEP 440: the release, and the commit as a local version label (as tirefe.__version__).
  set(TIREFE_PYTHON_VERSION ${PROJECT_VERSION})
  if(NOT TIREFE_GIT_COMMIT STREQUAL "unknown")
    set(TIREFE_PYTHON_VERSION "${PROJECT_VERSION}+g${TIREFE_GIT_COMMIT}")
  endif()
  set(TIREFE_DIST_INFO tirefe-${TIREFE_PYTHON_VERSION}.dist-info)
  pybind11_add_module(tirefe_python MODULE NO_EXTRAS src/python/tirefe_module.cpp)
  target_include_directories(tirefe_python PRIVATE src ${CMAKE_BINARY_DIR}/generated ${KLU_INCLUDE_DIR})
  target_link_libraries(tirefe_python PRIVATE tirefe::tirefe Eigen3::Eigen PkgConfig::LUA ${CMAKE_DL_LIBS})
  file(RELATIVE_PATH TIREFE_PYTHON_TO_LIBDIR ${CMAKE_INSTALL_PREFIX}/${TIREFE_INSTALL_PYTHON_DIR}/tirefe
       ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR})
  set_target_properties(tirefe_python PROPERTIES OUTPUT_NAME _core
    LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/python/tirefe INSTALL_RPATH "$ORIGIN/${TIREFE_PYTHON_TO_LIBDIR}")
  file(GLOB TIREFE_PYTHON_FILES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/python/tirefe/*)
  foreach(file ${TIREFE_PYTHON_FILES})
    get_filename_component(name ${file} NAME)
    configure_file(${file} ${CMAKE_BINARY_DIR}/python/tirefe/${name} COPYONLY)
  endforeach()
  set(TIREFE_DIST_INFO_DIR ${CMAKE_BINARY_DIR}/python/${TIREFE_DIST_INFO})
  file(GLOB TIREFE_OLD_DIST_INFO LIST_DIRECTORIES true ${CMAKE_BINARY_DIR}/python/tirefe-*.dist-info)
  list(REMOVE_ITEM TIREFE_OLD_DIST_INFO ${TIREFE_DIST_INFO_DIR})
  if(TIREFE_OLD_DIST_INFO)
    file(REMOVE_RECURSE ${TIREFE_OLD_DIST_INFO})  # of an earlier commit
  endif()
  configure_file(cmake/python_METADATA.in ${TIREFE_DIST_INFO_DIR}/METADATA @ONLY)
  file(WRITE ${TIREFE_DIST_INFO_DIR}/INSTALLER "cmake\n")
  file(WRITE ${TIREFE_DIST_INFO_DIR}/top_level.txt "tirefe\n")
  install(TARGETS tirefe_python LIBRARY DESTINATION ${TIREFE_INSTALL_PYTHON_DIR}/tirefe)
  install(FILES ${TIREFE_PYTHON_FILES} DESTINATION ${TIREFE_INSTALL_PYTHON_DIR}/tirefe)
  install(DIRECTORY ${TIREFE_DIST_INFO_DIR} DESTINATION ${TIREFE_INSTALL_PYTHON_DIR})
  install(CODE "execute_process(COMMAND ${PYTHON_EXECUTABLE} ${CMAKE_SOURCE_DIR}/cmake/write_record.py
    \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${TIREFE_INSTALL_PYTHON_DIR}\" ${TIREFE_DIST_INFO} tirefe
    RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR \"cannot write the RECORD of ${TIREFE_DIST_INFO}\")
  endif()")
endif()

# The cost of the C API and the FMU over the C++ interface (docs/coupling.md).
add_executable(bench_capi_step bench/capi/bench_capi_step.cpp)
target_include_directories(bench_capi_step PRIVATE src ${CMAKE_BINARY_DIR}/generated ${KLU_INCLUDE_DIR})
target_link_libraries(bench_capi_step PRIVATE tirefe::tirefe Eigen3::Eigen PkgConfig::LUA ${CMAKE_DL_LIBS})
target_compile_definitions(bench_capi_step PRIVATE TIREFE_FMU_BINARY="$<TARGET_FILE:tirefe_fmu>"
  TIREFE_FMU_GUID="${TIREFE_FMU_GUID}" TIREFE_FMU_RESOURCES="${TIREFE_FMU_DIR}/resources")
add_dependencies(bench_capi_step tirefe_tire_fmu)

# The C API's step on a rough road with cleats, as a real-time host sees it (docs/performance.md).
add_executable(bench_rough_road bench/capi/bench_rough_road.cpp)
target_link_libraries(bench_rough_road PRIVATE tirefe::tirefe)
