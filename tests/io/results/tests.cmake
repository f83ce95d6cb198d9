# Result files (JOB.h5, JOB.xdmf, JOB.sta, JOB.msg). Included from tests/io/CMakeLists.txt.
xpl_add_test_executable(
  xpl_tests_io_results results/test_result_files.cpp results/test_result_errors.cpp
  results/test_result_shells.cpp results/test_output_schedule_shells.cpp results/test_output_schedule_merge.cpp
  results/test_results_python.cpp results/test_import_state.cpp
  results/test_output_variables.cpp results/test_progress_line.cpp)
target_link_libraries(xpl_tests_io_results PRIVATE xpl::io_results hdf5::hdf5)
set(XPL_RESULTS_PYTHON_DIR ${CMAKE_CURRENT_BINARY_DIR}/results_python)
target_compile_definitions(xpl_tests_io_results
                           PRIVATE XPL_RESULTS_PYTHON_DIR="${XPL_RESULTS_PYTHON_DIR}")

# The files must open in h5py and meshio (the XDMF as ParaView sees it): the hidden [python]
# test cases write them (a hex model and a hex between two shells), then check_results.py
# reads them.
add_test(NAME io_results_python_write COMMAND xpl_tests_io_results "[python]")
set_tests_properties(io_results_python_write PROPERTIES FIXTURES_SETUP xpl_results_python)
foreach(job tiny mixed)
  add_test(NAME io_results_python_check_${job}
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/results/check_results.py
                   ${XPL_RESULTS_PYTHON_DIR} ${job})
  set_tests_properties(io_results_python_check_${job}
                       PROPERTIES FIXTURES_REQUIRED xpl_results_python LABELS "io;results;python")
endforeach()
