# A real scheduler and the installed tree (scripts in tests/slurm/). Included by
# tests/CMakeLists.txt. Each keeps at most one core busy (CPU time over wall time alone on
# the 2-core machine 0.4 and 0.9), so ctest -j2 runs another test beside it.
#
# slurm.sweep_cancel_resubmit starts a private single-node Slurm (Debian's slurmctld,
# slurmd and munge, installed with apt-get when missing; root only), submits
# pipelines/slurm_sweep.sbatch, cancels it with scancel part-way, resubmits it and
# compares the final file with a plain run's. Where it cannot run (not root, packages
# not installable, daemons not starting) it exits 77 with the reason: ctest shows it as
# skipped, not passed. Label `slurm`; `ctest -L slurm` runs it alone.
add_test(NAME slurm.sweep_cancel_resubmit
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/slurm_sweep.sh $<TARGET_FILE:hexdyn>
                 ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/slurm_tests/sweep_cancel_resubmit
                 ${HEXDYN_PYTHON})
set_tests_properties(slurm.sweep_cancel_resubmit PROPERTIES
                     SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "slurm;mpi")

# `cmake --install` into a temporary prefix; the installed binary, analysis, schema
# header and job script work without the repository.
add_test(NAME install.prefix
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/install_prefix.sh ${CMAKE_COMMAND}
                 ${CMAKE_BINARY_DIR} ${CMAKE_CURRENT_BINARY_DIR}/slurm_tests/install_prefix
                 ${HEXDYN_PYTHON})
set_tests_properties(install.prefix PROPERTIES
                     TIMEOUT 300 LABELS "install;mpi")
