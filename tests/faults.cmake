# Fault injection (docs/user/faults.md): links in a checkpoint, full disks,
# signals, a checkpoint lost mid-sweep, orphaned ranks, leftover temporary files. Scripts
# in tests/faults/, on the smoke sweep and tests/faults/slow.yaml. Included by
# tests/CMakeLists.txt; each test works in build/tests/fault_tests/<name>/ and keeps at most
# one core busy (its CPU time over its wall time alone on the 2-core machine is at most 1.0),
# so ctest -j2 runs another test beside it (PROCESSORS 1, the default). A test that needs
# root (a tmpfs to fill) exits 77 without it, which ctest reports as skipped, with the reason
# in its output.
set(HEXDYN_FAULT_TESTS links full_disk signals signals_mpirun lost_checkpoint orphans leftovers
                       inputs text readers sizes urdf_values replay messages)
# Python's writer of a read result (Result.write): signals, long names, a full disk.
list(APPEND HEXDYN_FAULT_TESTS python_writer)
foreach(test_name IN LISTS HEXDYN_FAULT_TESTS)
  add_test(NAME faults.${test_name}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/faults/${test_name}.sh $<TARGET_FILE:hexdyn>
                   ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/fault_tests/${test_name}
                   ${HEXDYN_MPIEXEC} ${HEXDYN_PYTHON})
  set_tests_properties(faults.${test_name} PROPERTIES
                       TIMEOUT 180 SKIP_RETURN_CODE 77
                       LABELS "faults;sweep")
endforeach()
