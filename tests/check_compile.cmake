# check_compile.cmake - runs one compiler command and checks that it fails or succeeds as
# expected, and why. ctest's own WILL_FAIL / PASS_REGULAR_EXPRESSION each look at only one
# of exit status and output; a bad configuration must produce both a non-zero exit status
# and its own #error, and nothing else.
#
#   cmake -DEXPECT=pass|fail [-DEXPECT_TEXT=...] [-DEXPECT_FROM=<file>] [-DNAME=...]
#         -P tests/check_compile.cmake -- <compiler> <arguments...>
#
# EXPECT=pass  the command must exit 0 with no diagnostics at all (so -Werror is not needed
#              to notice a warning).
# EXPECT=fail  the command must exit non-zero and its output must contain EXPECT_TEXT
#              (a literal string, not a regex). With EXPECT_FROM, the text is read from the
#              line "expect-error: <text>" of that file (tests/config/bad_*.h say which
#              #error they must trigger) and the output must hold exactly one #error
#              diagnostic, `#error "<text>...`: the configuration trips the check it was
#              written for, and only that one.
# On success prints "check_compile: PASS <NAME>", which the ctest entry also matches.

cmake_minimum_required(VERSION 3.25)

set(cmd "")
set(seen_dashes FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(seen_dashes)
    list(APPEND cmd "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(seen_dashes TRUE)
  endif()
endforeach()
if(NOT cmd)
  message(FATAL_ERROR "check_compile: no command after --")
endif()
if(NOT EXPECT STREQUAL "pass" AND NOT EXPECT STREQUAL "fail")
  message(FATAL_ERROR "check_compile: EXPECT must be pass or fail")
endif()

set(exactly_one_error FALSE)
if(EXPECT_FROM)
  file(STRINGS "${EXPECT_FROM}" lines REGEX "expect-error: ")
  if(NOT lines MATCHES "expect-error: (.*[^ */])")
    message(FATAL_ERROR "check_compile: ${EXPECT_FROM} has no 'expect-error: <text>' line")
  endif()
  set(EXPECT_TEXT "#error \"${CMAKE_MATCH_1}")
  set(exactly_one_error TRUE)
endif()

execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
string(REPLACE ";" " " shown "${cmd}")
set(ctx "command: ${shown}\nexit status: ${rc}\noutput:\n${out}")

if(EXPECT STREQUAL "pass")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "check_compile: expected the compile to succeed\n${ctx}")
  endif()
  string(STRIP "${out}" stripped)
  if(NOT stripped STREQUAL "")
    message(FATAL_ERROR "check_compile: expected no diagnostics\n${ctx}")
  endif()
else()
  if(rc EQUAL 0)
    message(FATAL_ERROR "check_compile: expected the compile to FAIL, but it succeeded\n${ctx}")
  endif()
  if(EXPECT_TEXT)
    string(FIND "${out}" "${EXPECT_TEXT}" pos)
    if(pos EQUAL -1)
      message(FATAL_ERROR "check_compile: the compile failed, but not with the expected\n  ${EXPECT_TEXT}\n${ctx}")
    endif()
  endif()
  if(exactly_one_error)
    string(REGEX MATCHALL "error: #error" errors "${out}")
    list(LENGTH errors nerrors)
    if(NOT nerrors EQUAL 1)
      message(FATAL_ERROR "check_compile: expected exactly one #error, got ${nerrors}\n${ctx}")
    endif()
  endif()
endif()
message("check_compile: PASS ${NAME}")
