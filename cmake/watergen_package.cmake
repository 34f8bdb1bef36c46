# `cmake --install` of the package an engine consumes with find_package(watergen CONFIG):
# watergen::runtime (watergen_engine and the reflection types it exposes), the imported
# executable watergen::watergen, their headers, and watergen_add_shaders(). Components:
# "runtime" (library and headers), "generator" (the executable), "cmake" (the package files).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(WATERGEN_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/watergen)
install(TARGETS watergen_engine watergen_reflection EXPORT watergenTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
install(TARGETS watergen EXPORT watergenTargets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT generator)
install(FILES
    runtime/include/watergen/runtime/reflection.h
    runtime/include/watergen/runtime/build_pass.h
    runtime/include/watergen/runtime/shader_build.h
    runtime/include/watergen/runtime/uniform_writer.h
    runtime/include/watergen/runtime/variant_pipeline.h
    runtime/include/watergen/runtime/pass_pipeline.h
    runtime/include/watergen/runtime/headless_gpu.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/watergen/runtime COMPONENT runtime)
install(EXPORT watergenTargets NAMESPACE watergen:: DESTINATION ${WATERGEN_PACKAGE_DIR}
  COMPONENT cmake)
configure_package_config_file(cmake/watergenConfig.cmake.in
  ${PROJECT_BINARY_DIR}/watergenConfig.cmake INSTALL_DESTINATION ${WATERGEN_PACKAGE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/watergenConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/watergenConfig.cmake
    ${PROJECT_BINARY_DIR}/watergenConfigVersion.cmake cmake/watergen_add_shaders.cmake
  DESTINATION ${WATERGEN_PACKAGE_DIR} COMPONENT cmake)
