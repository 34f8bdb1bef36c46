# watergen_add_shaders(<target> MATERIAL <file> [SCENES <files...>] [OUTPUT_DIR <dir>]
#                      [MODE permutations|specialized|branching] [FREEZE] [JOBS <n>] [CACHE <dir>])
#
# Runs `watergen build` as a build step of <target>: the build directory (manifest.json and one
# directory per shader) goes to OUTPUT_DIR (default: <current binary dir>/watergen/<target>).
# The step reruns only when its depfile (`watergen build --depfile`, which lists the material,
# the scenes and every file they include) names a changed file, or when watergen itself
# changed; otherwise the build has no work to do. An invalid material or shader fails the build
# with watergen's diagnostics (file:line:column). Sets the target property WATERGEN_SHADER_DIR
# to the output directory. JOBS and CACHE are watergen build's --jobs and --cache.
function(watergen_add_shaders target)
  cmake_parse_arguments(WG "FREEZE" "MATERIAL;OUTPUT_DIR;MODE;JOBS;CACHE" "SCENES" ${ARGN})
  if(NOT TARGET ${target})
    message(FATAL_ERROR "watergen_add_shaders: '${target}' is not a target")
  endif()
  if(NOT WG_MATERIAL)
    message(FATAL_ERROR "watergen_add_shaders(${target}): MATERIAL <file> is required")
  endif()
  if(WG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "watergen_add_shaders(${target}): unknown arguments ${WG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT WG_OUTPUT_DIR)
    set(WG_OUTPUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/watergen/${target}")
  endif()
  get_filename_component(out "${WG_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  get_filename_component(material "${WG_MATERIAL}" ABSOLUTE)
  set(args build "${material}")
  set(scenes "")
  foreach(scene IN LISTS WG_SCENES)
    get_filename_component(scene "${scene}" ABSOLUTE)
    list(APPEND scenes "${scene}")
    list(APPEND args --scene "${scene}")
  endforeach()
  if(WG_MODE)
    list(APPEND args --mode ${WG_MODE})
  endif()
  if(WG_FREEZE)
    list(APPEND args --freeze)
  endif()
  if(WG_JOBS)
    list(APPEND args --jobs ${WG_JOBS})
  endif()
  if(WG_CACHE)
    list(APPEND args --cache "${WG_CACHE}")
  endif()
  set(manifest "${out}/manifest.json")
  set(depfile "${CMAKE_CURRENT_BINARY_DIR}/watergen_${target}.d")
  add_custom_command(
    OUTPUT "${manifest}"
    COMMAND watergen::watergen ${args} --out "${out}" --depfile "${depfile}"
    DEPENDS "${material}" ${scenes} watergen::watergen
    DEPFILE "${depfile}"
    COMMENT "watergen: shaders of ${WG_MATERIAL} for ${target}"
    VERBATIM)
  add_custom_target(${target}_watergen_shaders DEPENDS "${manifest}")
  add_dependencies(${target} ${target}_watergen_shaders)
  set_property(TARGET ${target} PROPERTY WATERGEN_SHADER_DIR "${out}")
endfunction()
