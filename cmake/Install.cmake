# Install: the stage libraries (exported as verifybench::STAGE with relocatable paths), their
# public headers (detail/ folders stay private), the CLI and the report scripts.
get_property(stage_targets GLOBAL PROPERTY VERIFYBENCH_STAGE_TARGETS)
install(TARGETS ${stage_targets} EXPORT verifybenchTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS verifybench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(stage ${VERIFYBENCH_STAGES})
  install(DIRECTORY ${stage}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/verifybench/${stage}
          FILES_MATCHING PATTERN "*.hpp" PATTERN "detail" EXCLUDE)
endforeach()
install(FILES ${VERIFYBENCH_BUILD_INCLUDE}/verifybench/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/verifybench)
install(PROGRAMS reports/plot_report.py reports/plot_loop.py reports/summarize.py reports/real_table.py
                 reports/robustness_table.py reports/check_schema.py reports/decisions.py
                 reports/separation.py reports/clique_table.py reports/peers_table.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/verifybench/reports)
install(FILES reports/report_io.py reports/plot_style.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/verifybench/reports)
install(FILES reports/schema/report.schema.json
        DESTINATION ${CMAKE_INSTALL_DATADIR}/verifybench/reports/schema)
install(EXPORT verifybenchTargets NAMESPACE verifybench::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/verifybench)
include(CMakePackageConfigHelpers)
configure_package_config_file(cmake/verifybenchConfig.cmake.in
  ${PROJECT_BINARY_DIR}/verifybenchConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/verifybench)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/verifybenchConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/verifybenchConfig.cmake
              ${PROJECT_BINARY_DIR}/verifybenchConfigVersion.cmake
              cmake/verifybenchDependencies.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/verifybench)
