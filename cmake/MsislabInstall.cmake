# `cmake --install`: the msislab executable in bin/; the scenes, scenarios and SLAM configs in
# share/msislab/ (a scenario names its mesh relative to itself, so the layout is the tree's); the
# core libraries (stats, geometry, sim, slam, eval), their headers under include/msislab/ and a
# CMake package, so that another project's `find_package(msislab)` gives msislab::stats,
# msislab::geometry, msislab::sim, msislab::slam and msislab::eval (examples/ holds two such
# projects). The file formats, settings, datasets, result folders, figures, pages and commands
# (io/, settings/, dataset/, results/, plot/, report/, app/) are not a library API: use the
# executable.
include(CMakePackageConfigHelpers)

install(TARGETS msislab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes ${PROJECT_SOURCE_DIR}/scenarios
                  ${PROJECT_SOURCE_DIR}/config
        DESTINATION ${CMAKE_INSTALL_DATADIR}/msislab COMPONENT runtime)

set(msislab_libraries msislab_stats msislab_geometry msislab_sim msislab_slam msislab_eval)
install(TARGETS ${msislab_libraries} EXPORT msislabTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
foreach(dir stats geometry sim slam eval)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/msislab
          COMPONENT development FILES_MATCHING PATTERN "*.hpp")
endforeach()
set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/msislab)
install(EXPORT msislabTargets NAMESPACE msislab:: DESTINATION ${config_dir}
        COMPONENT development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/msislabConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/msislabConfig.cmake
                              INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/msislabConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/msislabConfig.cmake
              ${PROJECT_BINARY_DIR}/msislabConfigVersion.cmake
        DESTINATION ${config_dir} COMPONENT development)

# CPack: two Debian packages, `cpack -G DEB` in the build directory.
#   msislab      the executable, scenes, scenarios and configs; its library dependencies found by
#                dpkg-shlibdeps, so `apt-get install ./msislab_*.deb` pulls them;
#   msislab-dev  the core libraries, headers and CMake package, with the -dev packages their
#                headers and exported targets need.
set(CPACK_PACKAGE_NAME msislab)
set(CPACK_PACKAGE_VENDOR "msislab")
set(CPACK_PACKAGE_CONTACT "msislab developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Testbed for underwater SLAM with a mechanically scanned imaging sonar")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME msislab)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "xvfb")  # figures drawn without a display
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME msislab-dev)
string(CONCAT CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
       "msislab (= ${PROJECT_VERSION}), libeigen3-dev (>= 3.4), libceres-dev (>= 2.1), "
       "libembree-dev (>= 3), libsleef-dev, libtbb-dev, libboost-dev (>= 1.74)")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SHLIBDEPS OFF)
include(CPack)
