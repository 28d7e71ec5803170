# Under MPI every rank computes cases, rank 0 too: mpirun -n 2 and -n 3 over 12 cases report
# "by rank: N0, N1[, N2]" with every count at least 1 and the counts summing to 12.
#
#   cmake -DRIGIDITY=<rigidity> -DMPIEXEC=<mpirun> -DWORK_DIR=<scratch> -P sweep_mpi_ranks_test.cmake
cmake_minimum_required(VERSION 3.22)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/sweep.yaml
     "parameters:\n  bodies.0.velocity: {linspace: [0.1, 0.9, 6]}\n  time.end: {values: [1, 2.5]}\n"
     "collect:\n  p_max: probe.wall.p.max\n")

foreach(ranks 2 3)
  execute_process(COMMAND ${MPIEXEC} --oversubscribe -n ${ranks} ${RIGIDITY} sweep sweep.yaml --out mpi${ranks}
                  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "mpirun -n ${ranks} sweep failed (${status}):\n${out}\n${err}")
  endif()
  if(NOT out MATCHES "by rank: ([0-9, ]+)\\)")
    message(FATAL_ERROR "mpirun -n ${ranks}: no cases by rank in the report:\n${out}")
  endif()
  string(REPLACE ", " ";" counts "${CMAKE_MATCH_1}")
  list(LENGTH counts reported)
  if(NOT reported EQUAL ranks)
    message(FATAL_ERROR "mpirun -n ${ranks}: ${reported} ranks reported:\n${out}")
  endif()
  set(total 0)
  foreach(count IN LISTS counts)
    if(count LESS 1)
      message(FATAL_ERROR "mpirun -n ${ranks}: a rank computed no case:\n${out}")
    endif()
    math(EXPR total "${total} + ${count}")
  endforeach()
  if(NOT total EQUAL 12)
    message(FATAL_ERROR "mpirun -n ${ranks}: the ranks computed ${total} cases, not 12:\n${out}")
  endif()
endforeach()
message(STATUS "every rank computed cases")
