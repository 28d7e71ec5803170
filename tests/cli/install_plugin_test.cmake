# The installable package, end to end: `cmake --install` the build into a fresh prefix, build the
# example plugin (examples/plugin/, a copy, as an outside project has it) against that prefix
# alone with find_package(rigidity), and run its scene with the installed `rigidity`; the plugin
# is found from the scene's `plugins` and from RIGIDITY_PLUGIN_PATH.
#
#   cmake -DBUILD_DIR=<rigidity build> -DSOURCE_DIR=<rigidity source> -DWORK_DIR=<scratch>
#         [-DCXX_COMPILER=...] [-DCXX_FLAGS=...] -P install_plugin_test.cmake
cmake_minimum_required(VERSION 3.22)
foreach(variable BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "${variable} is not set")
  endif()
endforeach()

# Runs a command; stops the test with its output if it fails. Its stdout is left in `output`.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "failed (${status}): ${command}\n--- stdout ---\n${out}\n--- stderr ---\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

function(expect text part what)
  string(FIND "${text}" "${part}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${what}: '${part}' not found in:\n${text}")
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
set(example ${WORK_DIR}/example)
file(REMOVE_RECURSE ${WORK_DIR})

# 1. The package: executable, libraries, headers (framework's, solvers', sweeps', generated) and CMake config.
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
file(GLOB_RECURSE config ${prefix}/*/rigidityConfig.cmake)
file(GLOB_RECURSE library ${prefix}/*/librigidity.so)
file(GLOB_RECURSE sweep_library ${prefix}/*/librigidity_sweep.so)
foreach(path ${prefix}/bin/rigidity ${prefix}/include/rigidity/plugins.hpp ${prefix}/include/rigidity/config.hpp
             ${prefix}/include/rigidity/solvers/solve.hpp ${prefix}/include/rigidity/sweep.hpp "${config}" "${library}"
             "${sweep_library}")
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "not installed: ${path}")
  endif()
endforeach()

# The example scenes, with the tables they read, run from the prefix.
run(${prefix}/bin/rigidity run ${prefix}/share/rigidity/configs/tabulated_wall_impact.yaml --out ${WORK_DIR}/shared
    --quiet)
foreach(path ${prefix}/share/rigidity/configs/paper_wall_impact.yaml ${prefix}/share/rigidity/sweeps/paper_velocity.yaml
             ${WORK_DIR}/shared/summary.json)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "not installed or not run: ${path}")
  endif()
endforeach()

# 2. The example plugin, built against the prefix only.
file(COPY ${SOURCE_DIR}/examples/plugin/ DESTINATION ${example} PATTERN build EXCLUDE)
set(configure ${CMAKE_COMMAND} -S ${example} -B ${example}/build -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
if(CXX_COMPILER)
  list(APPEND configure -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
run(${configure} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
run(${CMAKE_COMMAND} --build ${example}/build -j2)

# 3. The installed rigidity: its own materials, then the plugin the scene lists (relative to it).
run(${prefix}/bin/rigidity materials)
expect("${output}" "\ntabulated\n" "rigidity materials")
run(${prefix}/bin/rigidity run ${example}/murnaghan.yaml --out ${WORK_DIR}/out)
expect("${output}" "murnaghan.yaml): ok at t_end" "rigidity run")
file(READ ${WORK_DIR}/out/summary.json summary)
expect("${summary}" "\"status\": \"ok\"" "summary.json")
expect("${summary}" "\"kind\": \"separation\"" "summary.json")

# 4. The plugin found on RIGIDITY_PLUGIN_PATH instead.
run(${CMAKE_COMMAND} -E env RIGIDITY_PLUGIN_PATH=${example}/build ${prefix}/bin/rigidity materials murnaghan)
expect("${output}" "Murnaghan's solid" "rigidity materials murnaghan")

file(REMOVE_RECURSE ${WORK_DIR})
message(STATUS "installed into a prefix, built the example plugin against it, ran its scene: ok")
