# Runs COMMAND with an existing output directory OUT holding one file; passes when the exit
# code is EXPECTED_EXIT, the output matches REGEX, and (on failure) OUT still holds exactly
# that file, unchanged: bad input never leaves partial output.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
file(WRITE ${OUT}/previous.txt "the previous build's output\n")
include(${CMAKE_CURRENT_LIST_DIR}/expect_command.cmake) # exit code and output; sets rc
if(NOT rc STREQUAL "0")
  file(GLOB_RECURSE left RELATIVE ${OUT} ${OUT}/*)
  file(READ ${OUT}/previous.txt previous)
  if(NOT left STREQUAL "previous.txt" OR NOT previous STREQUAL "the previous build's output\n")
    message(FATAL_ERROR "the output directory changed: ${left}")
  endif()
  # No staging directory left beside it either.
  get_filename_component(parent ${OUT} DIRECTORY)
  get_filename_component(name ${OUT} NAME)
  file(GLOB stray ${parent}/${name}.tmp-* ${parent}/${name}.old*)
  if(stray)
    message(FATAL_ERROR "staging left behind: ${stray}")
  endif()
endif()
