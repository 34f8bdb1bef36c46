# watergen_add_generator(<name> SOURCES <files...>)
#
# Builds <name>, a project's own watergen generator: watergen's command line (every command:
# build, emit, render, probe, compare, pick, ...) with the project's nodes compiled in. Each
# source registers its nodes before main runs (WATERGEN_REGISTER_NODES, axis_registry.h): a
# choice on an existing axis (register_choice) or a whole new axis with its place in
# composition (register_axis). A node's one C++ definition gives the GLSL, the HLSL and the CPU
# evaluation, so it joins validation, render, probe, compare and pick with no other code.
# watergen_add_shaders(... GENERATOR <name>) builds shaders with it. A failed registration (a
# name in use, a bad compose_after) stops the generator at start with the registering file and
# line, exit 2. docs/authoring.md is the guide.
#
# Needs find_package(watergen CONFIG COMPONENTS generator) out of tree.
if(NOT WATERGEN_GENERATOR_MAIN)
  set(WATERGEN_GENERATOR_MAIN "${CMAKE_CURRENT_LIST_DIR}/generator_main.cpp")
endif()
set_property(GLOBAL PROPERTY WATERGEN_GENERATOR_MAIN "${WATERGEN_GENERATOR_MAIN}")

function(watergen_add_generator name)
  cmake_parse_arguments(G "" "" "SOURCES" ${ARGN})
  if(G_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "watergen_add_generator(${name}): unknown arguments ${G_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET watergen::cli)
    message(FATAL_ERROR "watergen_add_generator(${name}): watergen::cli is missing: "
      "find_package(watergen CONFIG REQUIRED COMPONENTS generator)")
  endif()
  get_property(main GLOBAL PROPERTY WATERGEN_GENERATOR_MAIN)
  add_executable(${name} "${main}" ${G_SOURCES})
  target_link_libraries(${name} PRIVATE watergen::cli)
  target_compile_features(${name} PRIVATE cxx_std_20)
  if(TARGET mimalloc AND NOT WATERGEN_SANITIZE)
    # A shared library the executable needs before libc: its malloc is the one every library
    # calls (glslang, SPIRV-Tools and SPIRV-Cross allocate small objects by the million).
    target_link_libraries(${name} PRIVATE mimalloc)
  endif()
endfunction()
