# `cmake --install build --prefix P` (docs/user/sweeps.md#an-installed-hexdyn): everything a
# cluster module needs, laid out so that the installed share/hexdyn/ mirrors the repository:
#   P/bin/hexdyn                                  the program
#   P/share/hexdyn/configs/                       scenes, sweeps, variants, study files
#   P/share/hexdyn/pipelines/                     shell pipelines and slurm_sweep.sbatch
#   P/share/hexdyn/analysis/*.py                  Python reader, checks and plots
#                                                 (PYTHONPATH entry: `import hexdyn_results`)
#   P/share/hexdyn/src/hexdyn/io/schema.hpp  the result schema the Python reader
#                                                 uses, at the same path relative to
#                                                 analysis/ as in the repository
# Included by the top-level CMakeLists.txt.
include(GNUInstallDirs)
set(HEXDYN_INSTALL_SHARE ${CMAKE_INSTALL_DATADIR}/hexdyn)

install(TARGETS hexdyn RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${HEXDYN_INSTALL_SHARE}/configs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/pipelines/ DESTINATION ${HEXDYN_INSTALL_SHARE}/pipelines
        FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                         WORLD_READ WORLD_EXECUTE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/analysis/ DESTINATION ${HEXDYN_INSTALL_SHARE}/analysis
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/src/hexdyn/io/schema.hpp
        DESTINATION ${HEXDYN_INSTALL_SHARE}/src/hexdyn/io)
