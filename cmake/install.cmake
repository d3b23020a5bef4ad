# `cmake --install build --prefix P` (docs/user/sweeps.md#an-installed-hexdyn): everything a
# cluster module needs, laid out so that the installed share/hexdyn/ mirrors the repository:
#   P/bin/hexdyn                                  the program
#   P/libexec/hexdyn/hexdyn-sweep                 `hexdyn sweep` (MPI), run by P/bin/hexdyn
#   P/share/hexdyn/configs/                       scenes, sweeps, variants, study files
#   P/share/hexdyn/pipelines/                     shell pipelines and slurm_sweep.sbatch
#   P/share/hexdyn/analysis/*.py                  Python checks and plots (they import the
#                                                 package hexdyn, cmake/python.cmake)
#   P/share/hexdyn/src/hexdyn/io/schema*.hpp      the file layouts, for reference
# Included by the top-level CMakeLists.txt.
include(GNUInstallDirs)
set(HEXDYN_INSTALL_SHARE ${CMAKE_INSTALL_DATADIR}/hexdyn)

install(TARGETS hexdyn RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# `hexdyn sweep` runs this one (cli/main.cpp): P/libexec/hexdyn/hexdyn-sweep.
install(TARGETS hexdyn_sweep_cli RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/hexdyn)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${HEXDYN_INSTALL_SHARE}/configs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/pipelines/ DESTINATION ${HEXDYN_INSTALL_SHARE}/pipelines
        FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                         WORLD_READ WORLD_EXECUTE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/analysis/ DESTINATION ${HEXDYN_INSTALL_SHARE}/analysis
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
file(GLOB hexdyn_installed_schema_headers ${PROJECT_SOURCE_DIR}/src/hexdyn/io/schema*.hpp)
install(FILES ${hexdyn_installed_schema_headers} DESTINATION ${HEXDYN_INSTALL_SHARE}/src/hexdyn/io)

# ---------------------------------------------------------------- the C++ package
# `find_package(hexdyn CONFIG REQUIRED)` + `target_link_libraries(app PRIVATE hexdyn::hexdyn)`
# (examples/custom_study/, tested by tests/install/downstream.sh):
#   P/lib/libhexdyn_<layer>.a                     every layer library of src/CMakeLists.txt
#   P/include/hexdyn/<folder>/*.hpp               the headers, as in src/hexdyn/
#   P/include/hexdyn/hexdyn.hpp, version.hpp      the umbrella header, the generated version
#   P/lib/cmake/hexdyn/hexdynConfig.cmake         + ConfigVersion, hexdynTargets.cmake
#                                                 (hexdyn::<layer>, hexdyn::hexdyn), and
#                                                 hexdynMpiTargets.cmake (hexdyn::mpi, loaded
#                                                 by find_package(hexdyn COMPONENTS mpi))
#   P/lib/pkgconfig/hexdyn.pc                     the same libraries for pkg-config
set(HEXDYN_LAYERS core model urdf_reader planning kinematics dynamics contact allocation
                  allocation_ipopt grip power drive balance pipeline process config io sweep envelope replay
                  replay_io robustness)
set(HEXDYN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/hexdyn)

# The layers name their include folders by absolute build paths: valid in the build tree
# only; installed, the headers are under P/include.
foreach(layer IN LISTS HEXDYN_LAYERS ITEMS mpi)
  set(target hexdyn_${layer})
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(dirs)
    set(wrapped "")
    foreach(d IN LISTS dirs)
      list(APPEND wrapped "$<BUILD_INTERFACE:${d}>")
    endforeach()
    list(APPEND wrapped "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${wrapped}")
  endif()
  # Position-independent: the Python module (cmake/python.cmake) links the same archives
  # into a shared object, and a downstream project may do the same.
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${layer} POSITION_INDEPENDENT_CODE ON)
endforeach()

# HDF5 is linked by the full paths FindHDF5 gave (src/CMakeLists.txt): installed, by the
# pkg-config module hdf5 instead (hexdynConfig.cmake), which needs no C compiler in the
# downstream project (FindHDF5 does) and no path of this machine; its high-level library
# (dimension scales, io/labels.cpp) is found next to it.
foreach(target hexdyn_io hexdyn_sweep)
  get_target_property(libs ${target} INTERFACE_LINK_LIBRARIES)
  set(relinked "")
  foreach(l IN LISTS libs)
    if(l IN_LIST HDF5_C_LIBRARIES OR l IN_LIST HDF5_HL_LIBRARIES)
      list(APPEND relinked "$<BUILD_INTERFACE:${l}>")
    else()
      list(APPEND relinked "${l}")
    endif()
  endforeach()
  list(APPEND relinked "$<INSTALL_INTERFACE:PkgConfig::HEXDYN_HDF5>")
  set_target_properties(${target} PROPERTIES INTERFACE_LINK_LIBRARIES "${relinked}")
endforeach()

# hexdyn::hexdyn: the stable entry points of <hexdyn/hexdyn.hpp> (scenes, runs, result
# files) and the sweep, envelope, replay and robustness libraries; not MPI.
add_library(hexdyn_package INTERFACE)
target_link_libraries(hexdyn_package INTERFACE hexdyn_pipeline hexdyn_io hexdyn_sweep
                                               hexdyn_envelope hexdyn_replay_io hexdyn_robustness)
set_target_properties(hexdyn_package PROPERTIES EXPORT_NAME hexdyn)
add_library(hexdyn::hexdyn ALIAS hexdyn_package)

list(TRANSFORM HEXDYN_LAYERS PREPEND hexdyn_ OUTPUT_VARIABLE layer_targets)
install(TARGETS ${layer_targets} hexdyn_package EXPORT hexdynTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS hexdyn_mpi EXPORT hexdynMpiTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT hexdynTargets NAMESPACE hexdyn:: DESTINATION ${HEXDYN_INSTALL_CMAKEDIR})
install(EXPORT hexdynMpiTargets NAMESPACE hexdyn:: DESTINATION ${HEXDYN_INSTALL_CMAKEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/hexdyn/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hexdyn
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*_detail.hpp" EXCLUDE)
install(FILES ${CMAKE_BINARY_DIR}/generated/hexdyn/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hexdyn)

include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hexdynConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/package/hexdynConfig.cmake
                              INSTALL_DESTINATION ${HEXDYN_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/hexdynConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/hexdynConfig.cmake
              ${CMAKE_BINARY_DIR}/package/hexdynConfigVersion.cmake
        DESTINATION ${HEXDYN_INSTALL_CMAKEDIR})

# pkg-config: the libraries of hexdyn::hexdyn in link order (static: every dependency is
# public).
set(HEXDYN_PC_LIBS "")
foreach(layer replay_io envelope sweep robustness replay io config process pipeline drive power grip allocation_ipopt
              allocation
              contact dynamics
              kinematics planning urdf_reader model core)
  string(APPEND HEXDYN_PC_LIBS " -lhexdyn_${layer}")
endforeach()
# HDF5's high-level library (dimension scales, io/labels.cpp): in the directory pkg-config's
# hdf5 module names with -L, which it does not list itself.
string(APPEND HEXDYN_PC_LIBS " -lhdf5_hl")
configure_file(${PROJECT_SOURCE_DIR}/cmake/hexdyn.pc.in ${CMAKE_BINARY_DIR}/package/hexdyn.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/package/hexdyn.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
