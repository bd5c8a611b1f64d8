# `cmake --install build --prefix P`: the pss executable, the headers, the static library
# and a CMake package, so that a project finds it with find_package(pss) and links pss::pss.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PSS_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pss)

install(TARGETS pss_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# pss_nifti carries the NIfTI libraries that the static library needs at link time.
install(TARGETS pss pss_nifti EXPORT pssTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/pss DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT pssTargets NAMESPACE pss:: DESTINATION ${PSS_CMAKE_INSTALL_DIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/pssConfig.cmake.in ${PROJECT_BINARY_DIR}/pssConfig.cmake
                              INSTALL_DESTINATION ${PSS_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pssConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pssConfig.cmake ${PROJECT_BINARY_DIR}/pssConfigVersion.cmake
        DESTINATION ${PSS_CMAKE_INSTALL_DIR})
