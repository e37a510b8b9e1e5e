# Install rules and the Debian package (`cpack -G DEB` in the build folder makes a3rig_*.deb):
#   <prefix>/bin/a3rig                          the program (its defaults are compiled in)
#   <prefix>/bin/a3rig-lcm-spy                  scripts/lcm-spy.sh
#   <prefix>/bin/a3rig-read-lcm-log             scripts/read_lcm_log.py
#   <prefix>/share/a3rig/                       scenarios, airframes, schemas, the default
#                                               configuration files, the LCM definitions;
#                                               shared/ here is where the installed a3rig looks
#                                               for the α³-Bench corpus (rigs/scenario/shared_dir.cpp)
#   <prefix>/share/java/a3lcm-types.jar         the Java LCM types (when javac was found)
#   <prefix>/lib/python3/dist-packages/a3lcm/   the Python LCM types
include(GNUInstallDirs)
set(A3_DATA_DESTINATION ${CMAKE_INSTALL_DATADIR}/a3rig)

install(TARGETS a3rig RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(PROGRAMS scripts/lcm-spy.sh DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME a3rig-lcm-spy)
install(PROGRAMS scripts/read_lcm_log.py DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME a3rig-read-lcm-log)

install(DIRECTORY rigs/scenarios/ DESTINATION ${A3_DATA_DESTINATION}/scenarios FILES_MATCHING PATTERN "*.json")
install(DIRECTORY dynamics/airframes/ DESTINATION ${A3_DATA_DESTINATION}/airframes FILES_MATCHING PATTERN "*.json")
install(FILES eval/schema/episode.schema.json rigs/schema/scenario.schema.json
        DESTINATION ${A3_DATA_DESTINATION}/schema)
install(FILES linkemu/slice_profiles.json bridge/fc/fc_params.default.json agent/tool_catalog.json
        DESTINATION ${A3_DATA_DESTINATION})
install(DIRECTORY lcmtypes/ DESTINATION ${A3_DATA_DESTINATION}/lcmtypes FILES_MATCHING PATTERN "*.lcm")

install(DIRECTORY ${A3_LCM_PYTHON_DIR}/a3lcm DESTINATION lib/python3/dist-packages
        FILES_MATCHING PATTERN "*.py")
if(A3_LCM_TYPES_JAR)
  install(FILES ${A3_LCM_TYPES_JAR} DESTINATION ${CMAKE_INSTALL_DATADIR}/java)
endif()

# The package: Depends from dpkg-shlibdeps on the program (the Debian runtime libraries), plus
# libjs-d3, which `a3rig run` inlines into report.html; Recommends what the scripts and the
# trajectory plot run.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME a3rig)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "co-simulation rig for LLM agents flying UAV missions over emulated 6G links")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "a3rig developers <a3rig@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libjs-d3")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox, python3, default-jre, liblcm-java, libjchart2d-java")
include(CPack)
