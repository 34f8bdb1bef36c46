# `cmake --install` of the package an engine consumes with find_package(watergen CONFIG):
# watergen::runtime (watergen_runtime and the reflection types it exposes), the imported
# executable watergen::watergen, their headers, and watergen_add_shaders(); optionally the
# headless device watergen::headless (find_package(watergen CONFIG COMPONENTS headless)).
# With COMPONENTS generator, the authoring API: watergen::generator (the IR and DSL, the axis
# registry and its nodes, materials, the build API, the evaluation layer), watergen::cli and
# watergen_add_generator(), for a project's own generator with its own nodes.
# Install components: "runtime" (library and headers), "headless" (the device's library,
# headers and targets file), "generator" (the executable), "authoring" (the generator's
# libraries, headers, entry point and targets file), "cmake" (the package files).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(WATERGEN_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/watergen)

# watergen_install_libraries(COMPONENT c EXPORT e FOLDER f TARGETS t... HEADERS h...): the static
# libraries into export set `e` and the headers into include/watergen/<f>, in component `c`.
function(watergen_install_libraries)
  cmake_parse_arguments(L "" "COMPONENT;EXPORT;FOLDER" "TARGETS;HEADERS" ${ARGN})
  install(TARGETS ${L_TARGETS} EXPORT ${L_EXPORT}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${L_COMPONENT})
  list(TRANSFORM L_HEADERS PREPEND runtime/include/watergen/${L_FOLDER}/)
  install(FILES ${L_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/watergen/${L_FOLDER}
    COMPONENT ${L_COMPONENT})
endfunction()

watergen_install_libraries(COMPONENT runtime EXPORT watergenTargets FOLDER runtime
  TARGETS watergen_runtime watergen_reflection
  HEADERS reflection.h host_values.h build_pass.h shader_build.h uniform_writer.h
          variant_pipeline.h water_grid.h
          binding_layout.h
          pass_pipeline.h spirv_check.h manifest_schema.h)
install(TARGETS watergen EXPORT watergenTargets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT generator)
install(EXPORT watergenTargets NAMESPACE watergen:: DESTINATION ${WATERGEN_PACKAGE_DIR}
  COMPONENT cmake)

# The headless device: its own export set, installed with its component, so that a prefix
# without it still loads (the config includes this targets file only when the component is
# asked for).
watergen_install_libraries(COMPONENT headless EXPORT watergenHeadlessTargets FOLDER headless
  TARGETS watergen_headless
  HEADERS headless_device.h offscreen_draw.h compute_job.h texture_data.h)
install(EXPORT watergenHeadlessTargets NAMESPACE watergen:: DESTINATION ${WATERGEN_PACKAGE_DIR}
  COMPONENT headless)

# The authoring API: every library of the generator, the headers a node needs, and the entry
# point watergen_add_generator() compiles. Its own export set and targets file, loaded only with
# COMPONENTS generator (which needs headless too).
set(WATERGEN_AUTHORING_LIBRARIES watergen_ir_core watergen_ir_emit watergen_ir_cpu
  watergen_ir_fold watergen_ir watergen_water watergen_caustics watergen_plan watergen_toolchain
  watergen_pipeline_output watergen_pipeline_cache watergen_pipeline_variant watergen_pipeline_jobs
  watergen_pipeline_manifest watergen_pipeline_record watergen_pipeline_shards
  watergen_pipeline_build watergen_pipeline watergen_runner watergen_eval_image watergen_eval_scene
  watergen_eval_draw watergen_eval_measure watergen_eval_probe watergen_eval_report
  watergen_eval_compare watergen_eval_bench watergen_eval watergen_cli watergen_generator)
foreach(library IN LISTS WATERGEN_AUTHORING_LIBRARIES)
  get_target_property(export_name ${library} EXPORT_NAME)
  if(NOT export_name)
    string(REGEX REPLACE "^watergen_" "" export_name ${library})
    set_target_properties(${library} PROPERTIES EXPORT_NAME ${export_name})
  endif()
endforeach()
install(TARGETS ${WATERGEN_AUTHORING_LIBRARIES} EXPORT watergenAuthoringTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT authoring)
# The headers a project's node includes: the IR and its DSL (ir/core), the axis registry, Surface
# and watergen's nodes, whose functions a node may call; the headers those include are among
# them (tests/package builds examples/custom_node against this install).
file(GLOB WATERGEN_NODE_HEADERS RELATIVE ${PROJECT_SOURCE_DIR}/generator/include
  ${PROJECT_SOURCE_DIR}/generator/include/watergen/ir/core/*.h
  ${PROJECT_SOURCE_DIR}/generator/include/watergen/water/nodes/*.h)
list(APPEND WATERGEN_NODE_HEADERS watergen/water/axis_registry.h watergen/water/node_catalog.h
  watergen/water/surface.h)
foreach(header IN LISTS WATERGEN_NODE_HEADERS)
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES generator/include/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${folder}
    COMPONENT authoring)
endforeach()
install(FILES generator/cli/main.cpp DESTINATION ${WATERGEN_PACKAGE_DIR}
  RENAME generator_main.cpp COMPONENT authoring)
install(EXPORT watergenAuthoringTargets NAMESPACE watergen:: DESTINATION ${WATERGEN_PACKAGE_DIR}
  COMPONENT authoring)

configure_package_config_file(cmake/watergenConfig.cmake.in
  ${PROJECT_BINARY_DIR}/watergenConfig.cmake INSTALL_DESTINATION ${WATERGEN_PACKAGE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/watergenConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/watergenConfig.cmake
    ${PROJECT_BINARY_DIR}/watergenConfigVersion.cmake cmake/watergen_add_shaders.cmake
    cmake/watergen_add_generator.cmake
  DESTINATION ${WATERGEN_PACKAGE_DIR} COMPONENT cmake)
