# cmake -P script of the package_consumer test (see CMakeLists.txt). Every step prints what it
# ran; a failed expectation stops with FATAL_ERROR and the step's output.
cmake_minimum_required(VERSION 3.25)

set(prefix ${WORK_DIR}/prefix)
set(src ${WORK_DIR}/src)
set(bld ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
# watergen's build cache for this test only.
set(ENV{XDG_CACHE_HOME} ${WORK_DIR}/cache)

# run(<name> <expect: ok|fail> <output variable> COMMAND...): runs, checks the exit status.
function(run name expect out)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc
    OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  set(text "${stdout}${stderr}")
  message(STATUS "[${name}] exit ${rc}\n${text}")
  if(expect STREQUAL "ok" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "[${name}] failed (exit ${rc})")
  elseif(expect STREQUAL "fail" AND rc EQUAL 0)
    message(FATAL_ERROR "[${name}] succeeded; expected it to fail")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(expect_match name text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "[${name}] output does not match '${regex}'")
  endif()
endfunction()

# Install only the package's components: first those an engine with its own device needs.
foreach(component runtime generator cmake)
  run(install-${component} ok out ${CMAKE_COMMAND} --install ${WATERGEN_BUILD_DIR}
      --prefix ${prefix} --component ${component})
endforeach()
if(EXISTS ${prefix}/include/watergen/headless)
  message(FATAL_ERROR "[install-runtime] the headless device's headers came with the runtime")
endif()

# An engine that links watergen::runtime alone: it configures and builds without the headless
# component, which it cannot ask for until that is installed.
set(engine ${WORK_DIR}/engine)
file(WRITE ${engine}/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(engine LANGUAGES CXX)
find_package(watergen 0.1 CONFIG REQUIRED)
find_package(watergen 0.1 CONFIG QUIET COMPONENTS headless)
if(watergen_FOUND)
  message(STATUS \"headless component: found\")
else()
  message(STATUS \"headless component: not installed\")
endif()
add_executable(engine engine.cpp)
target_link_libraries(engine PRIVATE watergen::runtime)
")
file(WRITE ${engine}/engine.cpp "#include \"watergen/runtime/shader_build.h\"
int main(int argc, char** argv) {
    std::string error;
    return argc > 1 && watergen::ShaderBuild::open(argv[1], &error) ? 0 : 1;
}
")
run(engine-configure ok out ${CMAKE_COMMAND} -S ${engine} -B ${engine}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix})
expect_match(engine-configure "${out}" "headless component: not installed")
run(engine-build ok out ${CMAKE_COMMAND} --build ${engine}/build)

run(install-headless ok out ${CMAKE_COMMAND} --install ${WATERGEN_BUILD_DIR}
    --prefix ${prefix} --component headless)

# The consumer and its material and scene, copied: the test edits them.
file(COPY ${WATERGEN_SOURCE_DIR}/examples/engine_consumer/ DESTINATION ${src})
file(COPY ${WATERGEN_SOURCE_DIR}/examples/materials/default.json DESTINATION ${WORK_DIR}/water)
file(COPY ${WATERGEN_SOURCE_DIR}/examples/scenes/open_ocean.json DESTINATION ${WORK_DIR}/water)
file(COPY ${WATERGEN_SOURCE_DIR}/examples/scenes/mountain_lake.json DESTINATION ${WORK_DIR}/water)
set(material ${WORK_DIR}/water/default.json)
set(scene ${WORK_DIR}/water/open_ocean.json)
# mountain_lake keeps caustics=area_ratio with Gerstner waves: the caustics pass end to end.
set(lake ${WORK_DIR}/water/mountain_lake.json)
# Two scenes are a list: an initial cache file keeps its ';' out of the command line.
file(WRITE ${WORK_DIR}/scenes.cmake "set(WATER_SCENES \"${scene};${lake}\" CACHE STRING \"\")\n")

run(configure ok out ${CMAKE_COMMAND} -C ${WORK_DIR}/scenes.cmake -S ${src} -B ${bld}
    -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_PREFIX_PATH=${prefix} -DWATER_MATERIAL=${material})

run(first-build ok out ${CMAKE_COMMAND} --build ${bld})
expect_match(first-build "${out}" "watergen: shaders of")
if(NOT EXISTS ${bld}/watergen/water_viewer/manifest.json)
  message(FATAL_ERROR "[first-build] no manifest.json in ${bld}/watergen/water_viewer")
endif()

# The depfile watergen wrote names the output manifest and the inputs.
file(READ ${bld}/watergen_water_viewer.d depfile)
expect_match(depfile "${depfile}" "water_viewer/manifest.json:")
expect_match(depfile "${depfile}" "water/default.json")
expect_match(depfile "${depfile}" "water/open_ocean.json")
expect_match(depfile "${depfile}" "water/mountain_lake.json")

# The runtime-only engine opens that build.
run(engine-open ok out ${engine}/build/engine ${bld}/watergen/water_viewer)

run(draw ok out ${bld}/water_viewer ${bld}/watergen/water_viewer ${WORK_DIR}/water.ppm
    open_ocean)
expect_match(draw "${out}" "selected fresnel=schlick")
expect_match(draw "${out}" "nearest kept variant: foam: shore -> none")
expect_match(draw "${out}" "one pipeline layout for every variant: binding map frequency_sets, 14 slots in 3 sets")
expect_match(draw "${out}" "watergen_shaders.h: interface [0-9]+ .[0-9]+ bytes, [1-9][0-9]* members computed on the host. packs the same bytes; WaterParams at set 2, binding 0")
expect_match(draw "${out}" "0 non-finite")

# An area_ratio variant: its caustics pass drawn first, its texture bound as caustics_map.
run(draw-caustics ok out ${bld}/water_viewer ${bld}/watergen/water_viewer
    ${WORK_DIR}/caustics.ppm mountain_lake area_ratio)
expect_match(draw-caustics "${out}" "scene mountain_lake: selected [^\n]*waves=gerstner")
expect_match(draw-caustics "${out}" "selected [^\n]*caustics=area_ratio")
expect_match(draw-caustics "${out}"
  "caustics pass area_ratio \\(passes/caustics-area_ratio-gerstner\\) drawn first: 64x64 R32_SFLOAT")
expect_match(draw-caustics "${out}" "bound as caustics_map")
expect_match(draw-caustics "${out}" "0 non-finite")

# A mesh variant: the installed generator builds examples/materials/mesh.json, and the consumer
# draws its mesh over the runtime library's clipmap grid.
file(COPY ${WATERGEN_SOURCE_DIR}/examples/materials/mesh.json DESTINATION ${WORK_DIR}/water)
run(mesh-build ok out ${prefix}/bin/watergen build ${WORK_DIR}/water/mesh.json
    --out ${WORK_DIR}/mesh-build)
run(draw-mesh ok out ${bld}/water_viewer ${WORK_DIR}/mesh-build ${WORK_DIR}/mesh.ppm - none
    mesh)
expect_match(draw-mesh "${out}" "selected [^\n]*geometry=mesh")
expect_match(draw-mesh "${out}" "mesh over the runtime's clipmap grid: [0-9]+ vertices")
expect_match(draw-mesh "${out}" "0 non-finite")

run(second-build ok out ${CMAKE_COMMAND} --build ${bld})
expect_match(second-build "${out}" "ninja: no work to do")

file(TOUCH ${scene})
run(touched-scene ok out ${CMAKE_COMMAND} --build ${bld})
expect_match(touched-scene "${out}" "watergen: shaders of")
run(after-touch ok out ${CMAKE_COMMAND} --build ${bld})
expect_match(after-touch "${out}" "ninja: no work to do")

# A broken material (a misspelt choice): the build fails with the material's file:line:column.
file(READ ${material} text)
string(REPLACE "\"schlick\", \"exact\"" "\"schlik\", \"exact\"" text "${text}")
file(WRITE ${material} "${text}")
run(broken-material fail out ${CMAKE_COMMAND} --build ${bld})
expect_match(broken-material "${out}"
  "default.json:[0-9]+:[0-9]+: error: [^\n]*unknown fresnel choice 'schlik'")
# The earlier build output is left as it was.
run(draw-after-failure ok out ${bld}/water_viewer ${bld}/watergen/water_viewer
    ${WORK_DIR}/water2.ppm open_ocean)
# A project's own nodes against the installed authoring API (COMPONENTS generator):
# examples/custom_node, copied out of the tree, builds its generator water_lab (the fog axis and
# a Fresnel choice in two source files), the lab material's shaders with it, and its lab_check
# (render, probe, compare of the new nodes).
run(install-authoring ok out ${CMAKE_COMMAND} --install ${WATERGEN_BUILD_DIR}
    --prefix ${prefix} --component authoring)
set(lab_src ${WORK_DIR}/custom_node)
set(lab_bld ${WORK_DIR}/custom_node-build)
file(COPY ${WATERGEN_SOURCE_DIR}/examples/custom_node/ DESTINATION ${lab_src})
run(lab-configure ok out ${CMAKE_COMMAND} -S ${lab_src} -B ${lab_bld} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix})
run(lab-build ok out ${CMAKE_COMMAND} --build ${lab_bld})
expect_match(lab-build "${out}" "watergen: shaders of [^\n]*lab.json for lab_shaders")
file(READ ${lab_bld}/watergen/lab_shaders/manifest.json lab_manifest)
expect_match(lab-manifest "${lab_manifest}" "fresnel=spherical_gaussian,[^\"]*,fog=rational")
run(lab-second-build ok out ${CMAKE_COMMAND} --build ${lab_bld})
expect_match(lab-second-build "${out}" "ninja: no work to do")
run(lab-check ok out ${CMAKE_COMMAND} --build ${lab_bld} --target lab_check)
# GLSL = HLSL, and GPU against the CPU reference within the bounds (render exits 1 otherwise).
expect_match(lab-check "${out}" "fresnel=spherical_gaussian,[^\n]*,fog=exponential on llvmpipe")
expect_match(lab-check "${out}" "max abs: glsl-hlsl 0,")
expect_match(lab-check "${out}" "glsl vs cpu float: [0-9]+ pixels over 5e-05, 0 of them over it")
expect_match(lab-check "${out}" "fog.rational \\(glsl path\\) on llvmpipe[^\n]*: 5 tuples")
expect_match(lab-check "${out}" "fog=rational +approximates")
expect_match(lab-check "${out}" "GLSL and HLSL images: bit-identical in every view")
if(NOT EXISTS ${lab_bld}/lab/compare/report.html)
  message(FATAL_ERROR "[lab-check] no compare report")
endif()
# The fog variant drawn by the installed example equals the in-tree generator's draw, to the bit.
run(lab-in-tree ok out ${WATER_LAB} render --fog exponential --fresnel spherical_gaussian
    --width 64 --height 64 --draws 1 --out ${WORK_DIR}/lab-in-tree)
file(GLOB out_of_tree ${lab_bld}/lab/render/*fog-exponential/glsl.pfm)
file(GLOB in_tree ${WORK_DIR}/lab-in-tree/*fog-exponential/glsl.pfm)
if(NOT out_of_tree OR NOT in_tree)
  message(FATAL_ERROR "[lab-in-tree] no fog render: '${out_of_tree}' '${in_tree}'")
endif()
get_filename_component(out_of_tree_dir ${out_of_tree} DIRECTORY)
foreach(pair "${out_of_tree};${in_tree}" "${out_of_tree};${out_of_tree_dir}/hlsl.pfm")
  list(GET pair 0 a)
  list(GET pair 1 b)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${a} ${b} RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "[lab-in-tree] ${a} and ${b} differ")
  endif()
endforeach()
message(STATUS "package_consumer: every step as expected")
