# cmake -P script of the package_shards test (see CMakeLists.txt): watergen_add_shaders(...
# SHARDS 4 JOB_POOL watergen) in a project built by Ninja writes, after its merge step, byte
# for byte what one `watergen build` writes; a second build has no work to do; a touched scene
# reruns the shards, which find themselves up to date, and so not the merge; a changed
# parameter value reruns both.
cmake_minimum_required(VERSION 3.25)

set(src ${WORK_DIR}/src)
set(bld ${WORK_DIR}/build)
set(ref ${WORK_DIR}/one-build)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${src})
set(ENV{XDG_CACHE_HOME} ${WORK_DIR}/cache)

function(run name out)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc
    OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  message(STATUS "[${name}] exit ${rc}\n${stdout}${stderr}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[${name}] failed (exit ${rc})")
  endif()
  set(${out} "${stdout}${stderr}" PARENT_SCOPE)
endfunction()

file(COPY ${WATERGEN_SOURCE_DIR}/examples/materials/default.json DESTINATION ${src}/water)
foreach(scene harbour_night mountain_lake open_ocean)
  file(COPY ${WATERGEN_SOURCE_DIR}/examples/scenes/${scene}.json DESTINATION ${src}/water)
endforeach()
file(WRITE ${src}/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(shards NONE)
add_executable(watergen::watergen IMPORTED)
set_target_properties(watergen::watergen PROPERTIES IMPORTED_LOCATION \"${WATERGEN}\")
include(\"${WATERGEN_SOURCE_DIR}/cmake/watergen_add_shaders.cmake\")
set_property(GLOBAL PROPERTY JOB_POOLS watergen=2)
add_custom_target(app ALL)
watergen_add_shaders(app MATERIAL water/default.json
  SCENES water/harbour_night.json water/mountain_lake.json water/open_ocean.json
  OUTPUT_DIR shaders SHARDS 4 JOB_POOL watergen)
")
run(configure out ${CMAKE_COMMAND} -S ${src} -B ${bld} -G Ninja)
run(build out ${CMAKE_COMMAND} --build ${bld} -- -v)
foreach(i 1 2 3 4)
  if(NOT out MATCHES "--shard ${i}/4")
    message(FATAL_ERROR "[build] no step ran shard ${i}/4")
  endif()
endforeach()
if(NOT out MATCHES "merge: 4 shards, 56 variants")
  message(FATAL_ERROR "[build] the merge step did not join the four shards")
endif()

# One build of the same material and scenes, then every file compared.
run(one-build out ${WATERGEN} build ${src}/water/default.json --scene ${src}/water/harbour_night.json
    ${src}/water/mountain_lake.json ${src}/water/open_ocean.json --out ${ref} --quiet)
file(GLOB_RECURSE merged RELATIVE ${bld}/shaders ${bld}/shaders/*)
file(GLOB_RECURSE single RELATIVE ${ref} ${ref}/*)
list(SORT merged)
list(SORT single)
if(NOT merged STREQUAL single)
  message(FATAL_ERROR "the merged build and one build hold different files")
endif()
list(LENGTH single count)
foreach(f IN LISTS single)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${bld}/shaders/${f} ${ref}/${f}
    RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${f} differs between the merged build and one build")
  endif()
endforeach()
message(STATUS "the merged build equals one build: ${count} files, byte for byte")

# The merge stored one build's record: one build of the same inputs into it does nothing.
run(build-into-merged out ${WATERGEN} build ${src}/water/default.json
    --scene ${src}/water/harbour_night.json --scene ${src}/water/mountain_lake.json
    --scene ${src}/water/open_ocean.json --out ${bld}/shaders)
if(NOT out MATCHES "56 variants up to date")
  message(FATAL_ERROR "[build-into-merged] expected the merged output to be up to date")
endif()

run(rebuild out ${CMAKE_COMMAND} --build ${bld})
if(NOT out MATCHES "no work to do")
  message(FATAL_ERROR "[rebuild] expected no work to do")
endif()
# Inputs change a second after the last build: file times come from a coarse clock, and a
# change in the same tick as ninja's record of the last build would look older than it.
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1)
file(TOUCH ${src}/water/open_ocean.json)
run(touched out ${CMAKE_COMMAND} --build ${bld} -- -v)
if(NOT out MATCHES "--shard 4/4" OR NOT out MATCHES "up to date" OR out MATCHES "merge: ")
  message(FATAL_ERROR "[touched] expected the shards to rerun up to date and no merge")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1)
file(READ ${src}/water/default.json material)
string(REPLACE "\"shore_hardness\": {\"value\": 1.0" "\"shore_hardness\": {\"value\": 1.5"
  changed "${material}")
if(changed STREQUAL material)
  message(FATAL_ERROR "the material's shore_hardness value was not found")
endif()
file(WRITE ${src}/water/default.json "${changed}")
run(changed out ${CMAKE_COMMAND} --build ${bld})
if(NOT out MATCHES "merge: 4 shards, 56 variants")
  message(FATAL_ERROR "[changed] a changed material did not rerun the merge")
endif()
