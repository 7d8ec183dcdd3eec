# The find_package consumer check (label `package`), included by tests/CMakeLists.txt.
#
#   package_install                        installs this build tree into <build>/package-test/install
#                                          (fixture setup: first brings the installed targets up to date)
#   package_consumer_configure_build_run   configures tests/find_package against that prefix with
#                                          find_package(Krug CONFIG REQUIRED), builds it and runs it
#   package_config_dependencies            the installed KrugConfig.cmake names no optional (app-only)
#                                          dependency such as Cairo or a plotting library
#   package_staged_install_stays_under_its_prefix
#                                          installs with DESTDIR into a staging folder (no root
#                                          needed) and checks every file lands under the prefix
#
# Run with `ctest -L package` after building all targets.
set(KRUG_PACKAGE_TEST_DIR ${PROJECT_BINARY_DIR}/package-test)
set(KRUG_PACKAGE_PREFIX ${KRUG_PACKAGE_TEST_DIR}/install)

# Everything `cmake --install` copies must exist: the libraries and, when built, the app.
set(KRUG_PACKAGE_INSTALLED_TARGETS krug_mesh krug_contact krug_boundary krug_solver krug_setup krug_scenario krug_run krug_output)
if(TARGET krug_app)
  list(APPEND KRUG_PACKAGE_INSTALLED_TARGETS krug_app)
endif()

# The scripts get their settings from a generated file (one per configuration), so that lists such as
# CMAKE_PREFIX_PATH survive intact.
set(KRUG_PACKAGE_SETTINGS ${CMAKE_CURRENT_BINARY_DIR}/package_test_settings-$<CONFIG>.cmake)
file(GENERATE OUTPUT ${KRUG_PACKAGE_SETTINGS} CONTENT
"set(KRUG_BINARY_DIR [==[${PROJECT_BINARY_DIR}]==])
set(KRUG_PREFIX [==[${KRUG_PACKAGE_PREFIX}]==])
set(KRUG_INSTALLED_TARGETS [==[${KRUG_PACKAGE_INSTALLED_TARGETS}]==])
set(KRUG_CONSUMER_SOURCE [==[${CMAKE_CURRENT_LIST_DIR}]==])
set(KRUG_CONSUMER_BUILD [==[${KRUG_PACKAGE_TEST_DIR}/consumer-build]==])
set(KRUG_GENERATOR [==[${CMAKE_GENERATOR}]==])
set(KRUG_CXX_COMPILER [==[${CMAKE_CXX_COMPILER}]==])
set(KRUG_DEPENDENCY_PREFIX_PATH [==[${CMAKE_PREFIX_PATH}]==])
set(KRUG_BUILD_TYPE [==[$<IF:$<BOOL:$<CONFIG>>,$<CONFIG>,Release>]==])
")

add_test(NAME package_install
         COMMAND ${CMAKE_COMMAND} -DKRUG_SETTINGS=${KRUG_PACKAGE_SETTINGS} -DKRUG_STEP=install
                 -P ${CMAKE_CURRENT_LIST_DIR}/package_test.cmake)
set_tests_properties(package_install PROPERTIES
  LABELS package TIMEOUT 600 FIXTURES_SETUP krug_installed RESOURCE_LOCK krug_package_prefix)

add_test(NAME package_consumer_configure_build_run
         COMMAND ${CMAKE_COMMAND} -DKRUG_SETTINGS=${KRUG_PACKAGE_SETTINGS} -DKRUG_STEP=consumer
                 -P ${CMAKE_CURRENT_LIST_DIR}/package_test.cmake)
set_tests_properties(package_consumer_configure_build_run PROPERTIES
  LABELS package TIMEOUT 600 FIXTURES_REQUIRED krug_installed RESOURCE_LOCK krug_package_prefix)

add_test(NAME package_config_dependencies
         COMMAND ${CMAKE_COMMAND} -DKRUG_SETTINGS=${KRUG_PACKAGE_SETTINGS} -DKRUG_STEP=config
                 -P ${CMAKE_CURRENT_LIST_DIR}/package_test.cmake)
set_tests_properties(package_config_dependencies PROPERTIES
  LABELS package TIMEOUT 60 FIXTURES_REQUIRED krug_installed RESOURCE_LOCK krug_package_prefix)

add_test(NAME package_staged_install_stays_under_its_prefix
         COMMAND ${CMAKE_COMMAND} -DKRUG_SETTINGS=${KRUG_PACKAGE_SETTINGS} -DKRUG_STEP=staged
                 -DKRUG_STAGE=${KRUG_PACKAGE_TEST_DIR}/stage
                 -P ${CMAKE_CURRENT_LIST_DIR}/package_test.cmake)
set_tests_properties(package_staged_install_stays_under_its_prefix PROPERTIES
  LABELS package TIMEOUT 600 FIXTURES_REQUIRED krug_installed RESOURCE_LOCK krug_package_prefix)
