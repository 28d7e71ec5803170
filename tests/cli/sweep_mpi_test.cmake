# The same sweep serially and under MPI (mpirun --oversubscribe -n 2 and -n 3): the tables must
# match cell for cell but for wall_time_s, the last column.
#
#   cmake -DRIGIDITY=<rigidity> -DMPIEXEC=<mpirun> -DWORK_DIR=<scratch> -P sweep_mpi_test.cmake
cmake_minimum_required(VERSION 3.22)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/sweep.yaml
     "parameters:\n  bodies.0.velocity: {values: [0.1, 0.3, 0.5, 0.7, 0.9, 1.2]}\n  time.end: {values: [1, 2.5]}\n"
     "collect:\n  p_max: probe.wall.p.max\n  contact_time: event.separation.first.t\n  rebound: body.bar.velocity_mean\n")

function(table dir out)
  file(STRINGS ${WORK_DIR}/${dir}/sweep.csv lines)
  set(result "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE ",[^,]*$" "" line "${line}")
    string(APPEND result "${line}\n")
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

execute_process(COMMAND ${RIGIDITY} sweep sweep.yaml -j 1 --out serial --quiet WORKING_DIRECTORY ${WORK_DIR}
                RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "serial sweep failed (${status}): ${err}")
endif()
table(serial serial_table)
foreach(ranks 2 3)
  execute_process(COMMAND ${MPIEXEC} --oversubscribe -n ${ranks} ${RIGIDITY} sweep sweep.yaml --out mpi${ranks} --quiet
                  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "mpirun -n ${ranks} sweep failed (${status}):\n${out}\n${err}")
  endif()
  table(mpi${ranks} mpi_table)
  if(NOT mpi_table STREQUAL serial_table)
    message(FATAL_ERROR "mpirun -n ${ranks} gave another table:\n${mpi_table}\nserial:\n${serial_table}")
  endif()
endforeach()
string(FIND "${serial_table}" "invalid,2," invalid)
if(invalid EQUAL -1)
  message(FATAL_ERROR "the case at v = 1.2 is not an invalid row:\n${serial_table}")
endif()
message(STATUS "serial and MPI tables agree")
