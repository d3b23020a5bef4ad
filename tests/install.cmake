# hexdyn as a library (cmake/install.cmake, cmake/python.cmake, examples/). Included at the
# end of tests/CMakeLists.txt.

# The installed C++ package: examples/custom_study/ built against a temporary prefix alone
# reproduces, bit for bit, the file `hexdyn run` writes; pkg-config hexdyn links.
add_test(NAME install.downstream_cmake
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/install/downstream.sh ${CMAKE_COMMAND}
                 ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR} $<TARGET_FILE:hexdyn>
                 ${CMAKE_CURRENT_BINARY_DIR}/install_tests/downstream ${HEXDYN_PYTHON})
set_tests_properties(install.downstream_cmake PROPERTIES TIMEOUT 600 LABELS "install")

if(TARGET hexdyn_python)
  # The Python module from the build tree (tests/python/): runs bit for bit as the CLI, the
  # error family with the CLI's messages, threads (Ipopt scenes too), mutated scenes refused as
  # the CLI refuses them, one Result type for computed and read results and the readers of
  # every file kind (test_data.py), a URDF robot's stance fallback as a UserWarning
  # (test_stance.py), the required friction against HiGHS and cvxopt from the rows of
  # hexdyn.sample_problem (test_required_friction.py) and a run's per-sample values on fast
  # stairs gaits against HiGHS (test_required_friction_stairs.py), the functions' own
  # arguments refused in one line naming them (test_arguments.py).
  foreach(t run errors threads threads_ipopt mutations data stance required_friction
          required_friction_stairs arguments)
    add_test(NAME python.${t}
             COMMAND ${HEXDYN_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/python/test_${t}.py
                     $<TARGET_FILE:hexdyn> ${CMAKE_SOURCE_DIR})
    set_tests_properties(python.${t} PROPERTIES LABELS "python" TIMEOUT 300)
  endforeach()
  set_tests_properties(python.threads PROPERTIES PROCESSORS 2)
  # examples/optimize_duty_factor.py: scipy over hexdyn.run, in process (coarse tolerance).
  add_test(NAME examples.optimize_duty_factor
           COMMAND ${HEXDYN_PYTHON} ${CMAKE_SOURCE_DIR}/examples/optimize_duty_factor.py
                   ${CMAKE_SOURCE_DIR}/configs/paper.yaml --xatol 0.05)
  set_tests_properties(examples.optimize_duty_factor PROPERTIES LABELS "python;examples" TIMEOUT 300)
endif()

# Every test of this folder that runs Python finds the package hexdyn (reader and module) in
# the build tree, as the pipelines do (pipelines/setup.sh).
get_property(hexdyn_all_tests DIRECTORY PROPERTY TESTS)
foreach(t IN LISTS hexdyn_all_tests)
  set_property(TEST ${t} APPEND PROPERTY ENVIRONMENT "PYTHONPATH=${CMAKE_BINARY_DIR}/python")
endforeach()
