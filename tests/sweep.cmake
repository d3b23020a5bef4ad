# Parameter sweeps under MPI: whole-program tests of `hexdyn sweep` run plainly and under
# mpirun (scripts in tests/sweep/, Python checks with /usr/bin/python3). Included by
# tests/CMakeLists.txt. Each test works in build/tests/sweep_tests/<name>/. PROCESSORS
# counts the cores a test keeps busy, so that ctest -j2 never runs more than two cores' work:
# one, as the CPU time over the wall time of each test alone on the 2-core machine is at most
# 1.3 (ranks that wait, kills and resumes), and two for the grid accuracy check, whose two
# ranks compute throughout (1.9).
set(HEXDYN_MPIEXEC "${MPIEXEC_EXECUTABLE}")
if(NOT HEXDYN_MPIEXEC)
  set(HEXDYN_MPIEXEC mpirun)
endif()

# test name -> script in tests/sweep/
set(HEXDYN_SWEEP_TESTS
  "rank_invariance_1_2_4=rank_invariance"        # same scenario table (and runs) for 1, 2, 4 ranks
  "resume_after_kill=resume_after_kill"          # kill -9 of mpirun, --resume: same file, only missing recomputed
  "failing_scenario_recorded=failing_scenario"   # unreachable / out-of-range rows with messages; others complete
  "python_reader_and_heatmaps=reader_and_heatmaps"  # hexdyn.open_sweep reads it, plot_sweep.py draws it
  "bad_sweep_file_before_any_work=bad_sweep_file"   # exit 2, one line, no output, checkpoint kept
  "schema_declared_equals_written=schema_declared"  # io/schema.hpp as Python parses it = the files written
  "crash_contained=crash_contained"              # a scenario that aborts its process: crashed row, sweep completes, also on --resume
  "idle_ranks_do_not_spin=idle_ranks"            # ranks waiting for work use at most 10 % of a core each
  "resume_refused_after_edited_input=edited_inputs"  # an edited URDF or inherited scene refuses --resume, naming it
  "travel_same_distance=travel"                  # motion.travel: a duty-factor x speed sweep, every trunk moves two treads; travel with cycles is one line
  "cases_axis_over_robots=cases"                 # a cases axis over two URDF robots: every scenario ok, kept run = hexdyn run --set, labels in the file and readers
  "grid_accuracy_against_converged=grid_accuracy"  # output.tolerance 1e-4 on the stair check grid: energies within 1e-4, peak torques within 1e-3 of a converged grid
  "robustness_studies=robustness"                # studies per scenario: rows = the study alone, 1 rank = 2 ranks = killed and resumed
)
foreach(entry IN LISTS HEXDYN_SWEEP_TESTS)
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 test_name)
  list(GET pair 1 script)
  add_test(NAME sweep.${test_name}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sweep/${script}.sh $<TARGET_FILE:hexdyn>
                   ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/sweep_tests/${test_name}
                   ${HEXDYN_MPIEXEC} ${HEXDYN_PYTHON})
  set_tests_properties(sweep.${test_name} PROPERTIES
                       TIMEOUT 300 LABELS "sweep;mpi")
endforeach()
set_tests_properties(sweep.grid_accuracy_against_converged PROPERTIES PROCESSORS 2)
