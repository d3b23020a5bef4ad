# The Python module `hexdyn` (bindings/python/): the package's Python files, the schema module
# generated from io/schema.hpp and its compiled part hexdyn/_hexdyn*.so (pybind11), laid out as
# a package in the build tree,
#   build/python/hexdyn/{__init__,atomic_file,data,h5copy,h5files,results,schema,xr,_version,
#   _schema}.py, _hexdyn*.so
# (PYTHONPATH=build/python imports it: the tests and the pipelines set it), and installed to
#   P/lib/python3.X/dist-packages/hexdyn/
# which for the default prefix /usr/local is on Debian's /usr/bin/python3 path with no
# environment set (HEXDYN_PYTHON_INSTALL_DIR changes it). Included by the top-level
# CMakeLists.txt.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  # Debian's interpreter (numpy, h5py): another python3 may come first on PATH.
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  find_package(pybind11 CONFIG QUIET)
endif()
set(HEXDYN_PYTHON_PACKAGE_DIR ${CMAKE_BINARY_DIR}/python/hexdyn)
# The pure-Python files and the version: laid out at configure time, so that reading files (and
# the analysis scripts) needs no compiled part, only the schema module below.
set(hexdyn_python_files __init__.py atomic_file.py data.py energy.py h5copy.py h5files.py results.py schema.py
                        xr.py)
foreach(f IN LISTS hexdyn_python_files)
  configure_file(${PROJECT_SOURCE_DIR}/bindings/python/hexdyn/${f} ${HEXDYN_PYTHON_PACKAGE_DIR}/${f} COPYONLY)
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/bindings/python/hexdyn/_version.py.in
               ${HEXDYN_PYTHON_PACKAGE_DIR}/_version.py @ONLY)

# hexdyn/_schema.py, the HDF5 contracts as Python data, generated at build time from the
# compiled declarations of the schema headers (one source): cmake/schema_names.cmake lists the
# names the headers declare, bindings/python/schema/schema_py.cpp is compiled with them and
# prints the module. Built with the program `hexdyn` (and the module), so that the readers of
# a build tree work whenever the program does; needs no Python at build time.
# The headers in the order schema.hpp includes them at its end (the order of the declarations,
# and so of docs/user/output.md).
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                                       ${PROJECT_SOURCE_DIR}/src/hexdyn/io/schema.hpp)
file(STRINGS ${PROJECT_SOURCE_DIR}/src/hexdyn/io/schema.hpp hexdyn_schema_includes
     REGEX "^#include \"hexdyn/io/schema_[a-z_]+\\.hpp\"")
set(hexdyn_schema_headers ${PROJECT_SOURCE_DIR}/src/hexdyn/io/schema.hpp)
foreach(line ${hexdyn_schema_includes})
  string(REGEX REPLACE "^#include \"(hexdyn/io/schema_[a-z_]+\\.hpp)\".*" "\\1" header "${line}")
  list(APPEND hexdyn_schema_headers ${PROJECT_SOURCE_DIR}/src/${header})
endforeach()
set(hexdyn_schema_names ${CMAKE_BINARY_DIR}/schema_py/schema_names.inc)
add_custom_command(
  OUTPUT ${hexdyn_schema_names}
  COMMAND ${CMAKE_COMMAND} "-DHEADERS=${hexdyn_schema_headers}" -DOUT=${hexdyn_schema_names}
          -P ${PROJECT_SOURCE_DIR}/cmake/schema_names.cmake
  DEPENDS ${hexdyn_schema_headers} ${PROJECT_SOURCE_DIR}/cmake/schema_names.cmake
  COMMENT "Listing the declarations of the schema headers" VERBATIM)
add_executable(hexdyn_schema_py ${PROJECT_SOURCE_DIR}/bindings/python/schema/schema_py.cpp
                                ${hexdyn_schema_names})
target_include_directories(hexdyn_schema_py PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_compile_definitions(hexdyn_schema_py PRIVATE HEXDYN_SCHEMA_NAMES="${hexdyn_schema_names}")
target_compile_options(hexdyn_schema_py PRIVATE ${HEXDYN_WARNINGS})
set_target_properties(hexdyn_schema_py PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/schema_py)
add_custom_command(
  OUTPUT ${HEXDYN_PYTHON_PACKAGE_DIR}/_schema.py
  COMMAND hexdyn_schema_py ${HEXDYN_PYTHON_PACKAGE_DIR}/_schema.py
  DEPENDS hexdyn_schema_py
  COMMENT "Generating the Python schema module hexdyn/_schema.py" VERBATIM)
add_custom_target(hexdyn_python_schema ALL DEPENDS ${HEXDYN_PYTHON_PACKAGE_DIR}/_schema.py)
if(TARGET hexdyn)
  add_dependencies(hexdyn hexdyn_python_schema)
endif()
set(hexdyn_python_default OFF)
if(Python3_FOUND AND pybind11_FOUND)
  set(hexdyn_python_default ON)
endif()
option(HEXDYN_BUILD_PYTHON "Build the Python module hexdyn (pybind11)" ${hexdyn_python_default})
if(NOT HEXDYN_BUILD_PYTHON)
  message(STATUS "Python module hexdyn not built (needs python3-dev and pybind11-dev)")
  return()
endif()
if(NOT pybind11_FOUND)
  message(FATAL_ERROR "HEXDYN_BUILD_PYTHON=ON needs pybind11 (Debian: pybind11-dev, python3-dev)")
endif()

# lib/, not CMAKE_INSTALL_LIBDIR: Python's own layout, also on multiarch systems.
set(HEXDYN_PYTHON_INSTALL_DIR lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages
    CACHE STRING "Folder (relative to the prefix) the Python package hexdyn is installed into")

# NO_EXTRAS: no link-time optimisation of the glue (the libraries it links are not built
# for LTO; GCC would only warn about serial LTRANS jobs).
pybind11_add_module(hexdyn_python MODULE NO_EXTRAS ${PROJECT_SOURCE_DIR}/bindings/python/module.cpp
                    ${PROJECT_SOURCE_DIR}/bindings/python/forward_dynamics_args.cpp
                    ${PROJECT_SOURCE_DIR}/bindings/python/dynamics.cpp)
target_link_libraries(hexdyn_python PRIVATE hexdyn_pipeline hexdyn_io hexdyn_sweep yaml-cpp)
target_compile_options(hexdyn_python PRIVATE ${HEXDYN_WARNINGS})
set_target_properties(hexdyn_python PROPERTIES OUTPUT_NAME _hexdyn
                      LIBRARY_OUTPUT_DIRECTORY ${HEXDYN_PYTHON_PACKAGE_DIR})
add_dependencies(hexdyn_python hexdyn_python_schema)


install(TARGETS hexdyn_python LIBRARY DESTINATION ${HEXDYN_PYTHON_INSTALL_DIR}/hexdyn)
list(TRANSFORM hexdyn_python_files PREPEND ${HEXDYN_PYTHON_PACKAGE_DIR}/)
install(FILES ${hexdyn_python_files} ${HEXDYN_PYTHON_PACKAGE_DIR}/_version.py
              ${HEXDYN_PYTHON_PACKAGE_DIR}/_schema.py
        DESTINATION ${HEXDYN_PYTHON_INSTALL_DIR}/hexdyn)

# An Lmod module file for the installed tree (docs/user/sweeps.md#an-installed-hexdyn):
# P/share/hexdyn/modulefiles/hexdyn.lua, written at install time with the prefix the
# install was given (`cmake --install build --prefix P`), so that it puts P/bin on PATH and
# the installed package hexdyn on PYTHONPATH: the installed analysis/ scripts import it.
# tests/slurm/install_prefix.sh runs the installed tree with only what this file sets.
install(CODE "
  set(lua \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/hexdyn/modulefiles/hexdyn.lua\")
  file(WRITE \"\${lua}\" \"-- hexdyn ${PROJECT_VERSION}, installed in \${CMAKE_INSTALL_PREFIX}
local prefix = \\\"\${CMAKE_INSTALL_PREFIX}\\\"
prepend_path(\\\"PATH\\\", pathJoin(prefix, \\\"bin\\\"))
prepend_path(\\\"PYTHONPATH\\\", pathJoin(prefix, \\\"${HEXDYN_PYTHON_INSTALL_DIR}\\\"))
setenv(\\\"HEXDYN_SHARE\\\", pathJoin(prefix, \\\"${CMAKE_INSTALL_DATADIR}/hexdyn\\\"))
\")
  message(STATUS \"Installing: \${lua}\")")
