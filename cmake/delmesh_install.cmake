# Installation: `cmake --install build [--prefix DIR]` puts
#   bin/delmesh                                   the program;
#   lib/libdelmesh_{common,symbolic,solvers,meshing}.a   the libraries;
#   include/delmesh/{common,symbolic,solvers,meshing}/   their headers, included as in the sources
#                                                 ("meshing/driver/del_mesh.h");
#   lib/cmake/delmesh/                            delmeshConfig.cmake and the exported targets;
#   lib/python3/dist-packages/delmesh.*.so        the Python module, when it is built,
# so that a CMake project uses the libraries with
#   find_package(delmesh 0.1 REQUIRED)
#   target_link_libraries(app PRIVATE delmesh::meshing)
# (delmesh::common, delmesh::symbolic and delmesh::solvers name the lower modules).  The config
# finds the libraries' own dependencies again (GiNaC through pkg-config, CGAL, Eigen, TBB,
# nlohmann_json); MPFI, MPFR and GMP are linked by the paths found when delmesh was built.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(DELMESH_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/delmesh)
set(DELMESH_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/delmesh)

foreach(module common symbolic solvers meshing)
  set_target_properties(delmesh_${module} PROPERTIES EXPORT_NAME ${module})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/ DESTINATION ${DELMESH_INSTALL_INCLUDEDIR}/${module}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(TARGETS delmesh_common delmesh_symbolic delmesh_solvers delmesh_meshing EXPORT delmeshTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${DELMESH_INSTALL_INCLUDEDIR})
if(TARGET delmesh)
  install(TARGETS delmesh RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT delmeshTargets NAMESPACE delmesh:: DESTINATION ${DELMESH_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/delmeshConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/delmeshConfig.cmake
                              INSTALL_DESTINATION ${DELMESH_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/delmeshConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/delmeshConfig.cmake ${PROJECT_BINARY_DIR}/delmeshConfigVersion.cmake
        DESTINATION ${DELMESH_INSTALL_CMAKEDIR})

# A Debian package of the same files under /usr: `cpack -G DEB` in the build directory writes
# delmesh_<version>_<arch>.deb, its dependencies on shared libraries found by dpkg-shlibdeps.
set(CPACK_PACKAGE_NAME delmesh)
set(CPACK_PACKAGE_VENDOR "The delmesh developers")
set(CPACK_PACKAGE_CONTACT "The delmesh developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Certified meshing of smooth implicit surfaces (DelMesh)")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3-numpy")
include(CPack)
