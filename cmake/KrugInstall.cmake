# Install rules and the package config, so another project can say find_package(Krug CONFIG).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS krug ${KRUG_MODULE_TARGETS} EXPORT KrugTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/krug DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT KrugTargets NAMESPACE krug:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Krug)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/KrugConfig.cmake.in
  ${PROJECT_BINARY_DIR}/KrugConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Krug)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/KrugConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/KrugConfig.cmake ${PROJECT_BINARY_DIR}/KrugConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Krug)
