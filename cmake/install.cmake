# Install rules (included from the top-level CMakeLists.txt when GDCONTACT_INSTALL is on):
# the library, the public headers, a relocatable CMake package (find_package(gdcontact)), a
# pkg-config file (gdcontact.pc) and the licence.

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/gdcontact DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# Static (default): libgdcontact.a (adapter, C API) and libgdcontact_core.a (the core, usable
# without ODE). Shared: libgdcontact.so alone, the core inside.
set(_gdcontact_installed_targets gdcontact)
if(NOT BUILD_SHARED_LIBS)
  list(APPEND _gdcontact_installed_targets gdcontact_core)
endif()
install(TARGETS ${_gdcontact_installed_targets} EXPORT gdcontactTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# CMake: find_package(gdcontact) gives gdcontact::gdcontact (and gdcontact::core).
install(EXPORT gdcontactTargets NAMESPACE gdcontact::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gdcontact)
set(GDCONTACT_SHARED ${BUILD_SHARED_LIBS})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gdcontactConfig.cmake.in
  ${PROJECT_BINARY_DIR}/gdcontactConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gdcontact)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/gdcontactConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/gdcontactConfig.cmake
  ${PROJECT_BINARY_DIR}/gdcontactConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/gdcontact)

# pkg-config: `cc app.c $(pkg-config --cflags --libs gdcontact)`; with the static library,
# `pkg-config --static` adds what libgdcontact.a needs (the core archive, qhull, the C++ runtime).
if(BUILD_SHARED_LIBS)
  set(GDCONTACT_PC_LIBS_PRIVATE "")
else()
  set(GDCONTACT_PC_LIBS_PRIVATE "-lgdcontact_core -lqhull_r -lstdc++ -lm")
endif()
# The prefix is the one the files are installed under (`cmake --install --prefix`, CPack's
# staging), so the file is completed at install time: first everything else, then the prefix.
set(GDCONTACT_PC_PREFIX "@GDCONTACT_PC_PREFIX@")
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(GDCONTACT_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(GDCONTACT_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/cmake/gdcontact.pc.in ${PROJECT_BINARY_DIR}/gdcontact.pc.stage @ONLY)
install(CODE "
  set(GDCONTACT_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  configure_file(\"${PROJECT_BINARY_DIR}/gdcontact.pc.stage\" \"${PROJECT_BINARY_DIR}/gdcontact.pc\" @ONLY)
")
install(FILES ${PROJECT_BINARY_DIR}/gdcontact.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md
  DESTINATION ${CMAKE_INSTALL_DOCDIR})
