# cli_common.cmake -- helpers shared by the lsdem-shape end-to-end scripts (cmake -P).
# Needs TOOL (path to lsdem-shape) and WORK (scratch dir).

# run(expect_ok ARGS...): run the tool; fail the script when the exit status disagrees with
# expect_ok, or when a failure comes without a message naming the tool. Sets out and err.
function(run expect_ok)
  execute_process(COMMAND ${TOOL} ${ARGN} WORKING_DIRECTORY ${WORK}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(expect_ok AND NOT rc EQUAL 0)
    message(FATAL_ERROR "lsdem-shape ${ARGN}: exit ${rc}\n${out}${err}")
  elseif(NOT expect_ok AND rc EQUAL 0)
    message(FATAL_ERROR "lsdem-shape ${ARGN}: succeeded, expected a failure\n${out}")
  elseif(NOT expect_ok AND NOT err MATCHES "lsdem-shape")
    message(FATAL_ERROR "lsdem-shape ${ARGN}: failed without a message\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

# expect_in(text NEEDLES...): every needle occurs in text.
function(expect_in text)
  foreach(needle ${ARGN})
    string(FIND "${text}" "${needle}" at)
    if(at LESS 0)
      message(FATAL_ERROR "expected '${needle}' in:\n${text}")
    endif()
  endforeach()
endfunction()
