# CPack: a Debian package of the installed files (library, headers, CMake and pkg-config files,
# licence). Make it from a build directory with
#   cmake -S . -B build-deb -DCMAKE_INSTALL_PREFIX=/usr -DBUILD_SHARED_LIBS=ON \
#         -DGDCONTACT_BUILD_TESTS=OFF -DGDCONTACT_BUILD_SAMPLES=OFF
#   cmake --build build-deb && (cd build-deb && cpack -G DEB)    # → gdcontact_0.1.0_amd64.deb
#   apt-get install ./build-deb/gdcontact_0.1.0_amd64.deb
# (configured with the /usr prefix, GNUInstallDirs picks Debian's multiarch library directory).
# One package for library and development files, as Bullet's and ODE's users expect from a
# "-dev" package: its shared library's runtime dependencies come from dpkg-shlibdeps.
set(CPACK_PACKAGE_NAME gdcontact)
set(CPACK_PACKAGE_VENDOR "the gdcontact developers")
set(CPACK_PACKAGE_CONTACT "the gdcontact developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_GENERATOR DEB)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # gdcontact_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_NAME gdcontact)
set(CPACK_DEBIAN_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "the gdcontact developers")
set(CPACK_PACKAGE_DESCRIPTION
  "gdcontact computes contact manifolds between convex polytopes by the method of Silcowitz, \
Niebe and Erleben (SCA 2010) and plugs into the Open Dynamics Engine as a drop-in collider for \
box and convex geoms. C++ API (gdcontact/ode.hpp), C API (gdcontact/ode.h), CMake package and \
pkg-config file.")
# The headers include ODE's and Eigen's; the static library needs qhull at link time.
set(_gdcontact_deb_depends "libode-dev, libeigen3-dev, pkg-config")
if(BUILD_SHARED_LIBS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # libode8, libqhull-r8.0, libstdc++6, libc6 (dpkg-dev)
  set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)  # shlibs file and the ldconfig trigger
else()
  string(APPEND _gdcontact_deb_depends ", libqhull-dev")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${_gdcontact_deb_depends}")
include(CPack)
