# `cmake --install build --prefix P` lays crtforge out as include/crtforge/paths.hpp describes, so a
# separate CMake project finds it with find_package(crtforge) (CMAKE_PREFIX_PATH=P), and the
# installed copy can be moved: nothing in it names an absolute path.
#   P/bin/crtforge                      (component Runtime)
#   P/lib/crtforge/libcrtforge_imageio.so
#   P/share/crtforge/{templates,golden,tools,examples/webgpu}
#   P/include/crtforge/...              (component Development)
#   P/<libdir>/libcrtforge*.a, P/<libdir>/cmake/crtforge/
#   P/share/crtforge/tools/wgsl-runner/node_modules  (component Dawn: Dawn for the WGSL consumer)
#   P/share/crtforge/tools/godot4-runner/node_modules  (component Godot4: Godot 4.6 web build for the godot4 consumer)
install(TARGETS crtforge_core crtforge_runtime crtforge_reference crtforge_validate
        EXPORT crtforgeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT Development)
install(TARGETS crtforge RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT Runtime)
install(TARGETS crtforge_imageio LIBRARY DESTINATION lib/crtforge COMPONENT Runtime)

install(DIRECTORY include/crtforge DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT Development)
install(FILES ${PROJECT_BINARY_DIR}/include/crtforge/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/crtforge COMPONENT Development)

install(DIRECTORY templates golden DESTINATION share/crtforge COMPONENT Runtime)
install(DIRECTORY tools/godot3-runner DESTINATION share/crtforge/tools COMPONENT Runtime)
install(DIRECTORY tools/godot4-runner DESTINATION share/crtforge/tools COMPONENT Runtime
        PATTERN node_modules EXCLUDE)
install(DIRECTORY tools/godot4-runner/node_modules DESTINATION share/crtforge/tools/godot4-runner
        COMPONENT Godot4 OPTIONAL)
install(DIRECTORY tools/wgsl-runner DESTINATION share/crtforge/tools COMPONENT Runtime
        PATTERN node_modules EXCLUDE)
# check.mjs and the driver it loads: validate runs the package's framework adapters through it.
install(DIRECTORY examples/webgpu DESTINATION share/crtforge/examples COMPONENT Runtime
        PATTERN node_modules EXCLUDE)
install(DIRECTORY tools/wgsl-runner/node_modules DESTINATION share/crtforge/tools/wgsl-runner
        COMPONENT Dawn OPTIONAL)

install(EXPORT crtforgeTargets NAMESPACE crtforge:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/crtforge
        COMPONENT Development)
configure_package_config_file(cmake/crtforgeConfig.cmake.in ${PROJECT_BINARY_DIR}/crtforgeConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/crtforge)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/crtforgeConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/crtforgeConfig.cmake ${PROJECT_BINARY_DIR}/crtforgeConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/crtforge COMPONENT Development)
