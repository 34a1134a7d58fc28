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
# Relocatable: the prefix is derived from where the file is found (pkg-config's ${pcfiledir}), so a
# tree installed with one prefix and moved elsewhere, or the Debian package's files under /usr,
# describe themselves. The number of `..` is the depth of <libdir>/pkgconfig below the prefix:
# 2 for lib/pkgconfig, 3 for Debian's multiarch lib/x86_64-linux-gnu/pkgconfig. An absolute
# CMAKE_INSTALL_LIBDIR or INCLUDEDIR is written as it is (such an installation cannot move).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(GDCONTACT_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(GDCONTACT_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  file(RELATIVE_PATH _gdcontact_pc_up "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  string(REGEX REPLACE "/$" "" _gdcontact_pc_up "${_gdcontact_pc_up}")  # "../../" on some CMakes
  set(GDCONTACT_PC_PREFIX "\${pcfiledir}/${_gdcontact_pc_up}")
  set(GDCONTACT_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(GDCONTACT_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(GDCONTACT_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/gdcontact.pc.in ${PROJECT_BINARY_DIR}/gdcontact.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/gdcontact.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md
  DESTINATION ${CMAKE_INSTALL_DOCDIR})
