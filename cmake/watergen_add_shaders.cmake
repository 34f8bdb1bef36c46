# watergen_add_shaders(<target> MATERIAL <file> [SCENES <files...>] [OUTPUT_DIR <dir>]
#                      [MODE permutations|specialized|branching] [FREEZE] [JOBS <n>] [CACHE <dir>]
#                      [SHARDS <n> [JOB_POOL <pool>]] [BINDINGS <profile>|<file>]
#                      [GENERATOR <target>])
#
# Runs `watergen build` as a build step of <target>: the build directory (manifest.json and one
# directory per shader) goes to OUTPUT_DIR (default: <current binary dir>/watergen/<target>).
# The step reruns only when its depfile (`watergen build --depfile`, which lists the material,
# the scenes and every file they include) names a changed file, or when watergen itself
# changed; otherwise the build has no work to do. An invalid material or shader fails the build
# with watergen's diagnostics (file:line:column). Sets the target property WATERGEN_SHADER_DIR
# to the output directory, which also holds watergen_shaders.h, the build's C++ header (its
# binding map, uniform blocks as structs, variants; a target that includes it adds that
# directory to its include path). JOBS and CACHE are watergen build's --jobs and --cache; BINDINGS is
# its --bindings: a binding profile's name or the engine's binding map file (a file is a
# dependency like the material). GENERATOR is a project's own generator
# (watergen_add_generator: watergen with the project's nodes), run instead of watergen and a
# dependency of the step: the material may then offer the project's axes and choices.
#
# SHARDS <n> splits the build into n steps (by variant, or in specialized and branching mode by
# shader: no more useful steps than the build has shaders), `watergen build --shard i/n`
# each into <OUTPUT_DIR>.shards/<i> with a depfile of its own, and one `watergen merge` of them
# into OUTPUT_DIR, which is then byte for byte what one build writes. The shard steps are
# independent custom commands: the generator runs them in parallel (in the Ninja job pool
# JOB_POOL when given, e.g. set_property(GLOBAL PROPERTY JOB_POOLS watergen=4)), and a
# remote-execution launcher set as RULE_LAUNCH_CUSTOM runs them where it runs compiles.
# JOB_POOL puts the build step (or each shard step) in that Ninja job pool.
function(watergen_add_shaders target)
  cmake_parse_arguments(WG "FREEZE" "MATERIAL;OUTPUT_DIR;MODE;JOBS;CACHE;SHARDS;JOB_POOL;BINDINGS;GENERATOR"
    "SCENES" ${ARGN})
  if(NOT TARGET ${target})
    message(FATAL_ERROR "watergen_add_shaders: '${target}' is not a target")
  endif()
  if(NOT WG_MATERIAL)
    message(FATAL_ERROR "watergen_add_shaders(${target}): MATERIAL <file> is required")
  endif()
  if(WG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "watergen_add_shaders(${target}): unknown arguments ${WG_UNPARSED_ARGUMENTS}")
  endif()
  set(tool watergen::watergen)
  if(WG_GENERATOR)
    if(NOT TARGET ${WG_GENERATOR})
      message(FATAL_ERROR "watergen_add_shaders(${target}): GENERATOR ${WG_GENERATOR} is not a "
        "target (watergen_add_generator makes one)")
    endif()
    set(tool ${WG_GENERATOR})
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
  set(binding_file "")
  if(WG_BINDINGS)
    if(WG_BINDINGS MATCHES "^[a-z_]+$")
      list(APPEND args --bindings ${WG_BINDINGS}) # a profile
    else()
      get_filename_component(binding_file "${WG_BINDINGS}" ABSOLUTE)
      list(APPEND args --bindings "${binding_file}")
    endif()
  endif()
  set(manifest "${out}/manifest.json")
  set(pool "")
  if(WG_JOB_POOL)
    set(pool JOB_POOL ${WG_JOB_POOL})
  endif()
  if(WG_SHARDS)
    if(NOT WG_SHARDS MATCHES "^[1-9][0-9]*$")
      message(FATAL_ERROR "watergen_add_shaders(${target}): SHARDS ${WG_SHARDS}: expected a "
        "positive whole number")
    endif()
    set(shard_dirs "")
    set(shard_files "")
    foreach(i RANGE 1 ${WG_SHARDS})
      set(shard_dir "${out}.shards/${i}")
      set(depfile "${CMAKE_CURRENT_BINARY_DIR}/watergen_${target}_shard_${i}.d")
      add_custom_command(
        OUTPUT "${shard_dir}/manifest.json"
        COMMAND ${tool} ${args} --shard ${i}/${WG_SHARDS} --out "${shard_dir}"
          --depfile "${depfile}" --quiet
        DEPENDS "${material}" ${scenes} ${binding_file} ${tool}
        DEPFILE "${depfile}"
        ${pool}
        COMMENT "watergen: shard ${i}/${WG_SHARDS} of ${WG_MATERIAL} for ${target}"
        VERBATIM)
      list(APPEND shard_dirs "${shard_dir}")
      list(APPEND shard_files "${shard_dir}/manifest.json") # what the depfile names
    endforeach()
    add_custom_command(
      OUTPUT "${manifest}"
      BYPRODUCTS "${out}/watergen_shaders.h"
      COMMAND ${tool} merge "${out}" ${shard_dirs}
      DEPENDS ${shard_files} ${tool}
      COMMENT "watergen: merging ${WG_SHARDS} shards of ${WG_MATERIAL} for ${target}"
      VERBATIM)
  else()
    set(depfile "${CMAKE_CURRENT_BINARY_DIR}/watergen_${target}.d")
    add_custom_command(
      OUTPUT "${manifest}"
      BYPRODUCTS "${out}/watergen_shaders.h"
      COMMAND ${tool} ${args} --out "${out}" --depfile "${depfile}"
      DEPENDS "${material}" ${scenes} ${binding_file} ${tool}
      DEPFILE "${depfile}"
      ${pool}
      COMMENT "watergen: shaders of ${WG_MATERIAL} for ${target}"
      VERBATIM)
  endif()
  add_custom_target(${target}_watergen_shaders DEPENDS "${manifest}")
  add_dependencies(${target} ${target}_watergen_shaders)
  set_property(TARGET ${target} PROPERTY WATERGEN_SHADER_DIR "${out}")
endfunction()
