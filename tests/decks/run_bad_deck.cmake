# Runs `covcontact check DECK` in an empty scratch directory and asserts what the deck's header
# declares: "# expect-exit: N" (the exit code) and "# expect-message: TEXT" (a fragment of
# stderr), and that the command created no file there.
# Usage: cmake -DCOVCONTACT=<exe> -DDECK=<deck> -DSCRATCH=<dir> -P run_bad_deck.cmake
foreach(variable COVCONTACT DECK SCRATCH)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_bad_deck.cmake: -D${variable}=... is required")
  endif()
endforeach()

# The header is read with regexes on the whole text (not file(STRINGS)), so that semicolons in
# the expected message stay part of it instead of splitting it into a CMake list.
file(READ "${DECK}" deck_text)
if(NOT deck_text MATCHES "# expect-exit: ([0-9]+)")
  message(FATAL_ERROR "${DECK}: no '# expect-exit: N' header line")
endif()
set(expected_exit "${CMAKE_MATCH_1}")
if(NOT deck_text MATCHES "# expect-message: ([^\n]+)")
  message(FATAL_ERROR "${DECK}: no '# expect-message: TEXT' header line")
endif()
set(expected_message "${CMAKE_MATCH_1}")
string(STRIP "${expected_message}" expected_message)

file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}")
execute_process(
  COMMAND "${COVCONTACT}" check "${DECK}"
  WORKING_DIRECTORY "${SCRATCH}"
  RESULT_VARIABLE exit_code
  OUTPUT_VARIABLE standard_output
  ERROR_VARIABLE standard_error
  TIMEOUT 100)

set(failures "")
if(NOT "${exit_code}" STREQUAL "${expected_exit}")
  string(APPEND failures "exit code ${exit_code}, expected ${expected_exit}\n")
endif()
string(FIND "${standard_error}" "${expected_message}" found_at)
if(found_at EQUAL -1)
  string(APPEND failures "stderr lacks the expected fragment:\n  ${expected_message}\n")
endif()
file(GLOB_RECURSE created LIST_DIRECTORIES true "${SCRATCH}/*")
if(created)
  string(APPEND failures "files were created in the working directory: ${created}\n")
endif()

if(failures)
  message(FATAL_ERROR "covcontact check ${DECK}\n${failures}--- stdout ---\n${standard_output}"
                      "--- stderr ---\n${standard_error}")
endif()
message(STATUS "ok: exit ${exit_code}, stderr contains the expected fragment, no files created")
