# Finds the ODE gdcontact plugs into, where the user points: its pkg-config file ode.pc (through
# PKG_CONFIG_PATH or CMAKE_PREFIX_PATH; Debian's libode-dev and ODE's own CMake installation both
# write one), which gives the target PkgConfig::ODE the library and the installed CMake package
# (gdcontactConfig.cmake) link. Then it reads what that ODE is from its own headers — version,
# precision — and, where ODE was built with CMake (ode-config.cmake), its libccd options, and says
# all of it in one line of the configure output:
#   gdcontact: ODE 0.16.6 (<prefix>), double precision, shared, libccd: off (ode-config.cmake)
# What gdcontact cannot serve stops here, naming what was found and what is needed: no ODE, an ODE
# older than 0.16.2, headers of one ODE and ode.pc of another, a precision that is neither.
# Sets GDCONTACT_ODE_VERSION, GDCONTACT_ODE_PRECISION (double|single) and GDCONTACT_ODE_PC_PRECISION
# (dDOUBLE|dSINGLE, for the installed CMake package's check of the ODE a consumer finds).
find_package(PkgConfig QUIET)
if(NOT PKG_CONFIG_FOUND)
  message(FATAL_ERROR "gdcontact needs pkg-config to find ODE: install pkg-config (apt-get install pkg-config)")
endif()
# ODE built with CMake installs ode-config.cmake beside ode.pc: the one place its libccd options are
# written down. Looked for first (it sets ODE_* variables pkg-config then overrides): where the
# user points CMAKE_PREFIX_PATH at an ODE while pkg-config finds another (e.g. the system's),
# building against the wrong one silently is stopped below, naming both.
set(_gdcontact_ode_libccd "not recorded (ode.pc has no libccd options: an ODE built with autotools)")
set(_gdcontact_ode_config_prefix "")
find_package(ODE CONFIG QUIET)
if(ODE_FOUND AND ODE_DIR)
  get_filename_component(_gdcontact_ode_config_prefix "${ODE_DIR}/../../.." ABSOLUTE)
  if(ODE_WITH_LIBCCD)
    set(_gdcontact_ode_libccd_pairs "")
    foreach(_pair BOX_CYL CAP_CYL CYL_CYL CONVEX_BOX CONVEX_CAP CONVEX_CONVEX CONVEX_CYL CONVEX_SPHERE)
      if(ODE_WITH_LIBCCD_${_pair})
        string(TOLOWER "${_pair}" _pair)
        list(APPEND _gdcontact_ode_libccd_pairs "${_pair}")
      endif()
    endforeach()
    string(REPLACE ";" " " _gdcontact_ode_libccd_pairs "${_gdcontact_ode_libccd_pairs}")
    set(_gdcontact_ode_libccd "on for ${_gdcontact_ode_libccd_pairs} (ode-config.cmake)")
  else()
    set(_gdcontact_ode_libccd "off (ode-config.cmake)")
  endif()
endif()

pkg_check_modules(ODE QUIET IMPORTED_TARGET ode)   # the physics engine we plug into
if(NOT TARGET PkgConfig::ODE)
  if(_gdcontact_ode_config_prefix)
    set(_hint "; ODE's CMake package was found at ${ODE_DIR}: point PKG_CONFIG_PATH at ${_gdcontact_ode_config_prefix}/lib/pkgconfig")
  else()
    set(_hint "")
  endif()
  message(FATAL_ERROR "gdcontact needs ODE 0.16.2 or newer, found through its pkg-config file ode.pc: "
    "install libode-dev (apt-get install libode-dev), or point PKG_CONFIG_PATH (or CMAKE_PREFIX_PATH) "
    "at the ODE you built (<prefix>/lib/pkgconfig)${_hint}")
endif()
pkg_get_variable(_gdcontact_ode_prefix ode prefix)
pkg_get_variable(_gdcontact_ode_includedir ode includedir)
pkg_get_variable(_gdcontact_ode_pc_precision ode precision)
get_filename_component(_gdcontact_ode_where "${_gdcontact_ode_prefix}" ABSOLUTE)
if(_gdcontact_ode_config_prefix AND NOT _gdcontact_ode_config_prefix STREQUAL _gdcontact_ode_where)
  message(FATAL_ERROR "gdcontact found two ODEs: CMake's package ${ODE_DIR} (prefix "
    "${_gdcontact_ode_config_prefix}) and pkg-config's ode.pc (prefix ${_gdcontact_ode_where}). "
    "Point PKG_CONFIG_PATH at ${_gdcontact_ode_config_prefix}/lib/pkgconfig to use the first, or "
    "take it out of CMAKE_PREFIX_PATH to use the second.")
endif()

# The headers the build compiles against: ODE_INCLUDE_DIRS (empty for /usr/include) first.
set(_gdcontact_ode_header "")
foreach(_dir IN LISTS ODE_INCLUDE_DIRS _gdcontact_ode_includedir)
  if(NOT _gdcontact_ode_header AND EXISTS "${_dir}/ode/ode.h")
    set(_gdcontact_ode_header "${_dir}/ode")
  endif()
endforeach()
if(NOT _gdcontact_ode_header)
  message(FATAL_ERROR "gdcontact: ODE's ode.pc (${_gdcontact_ode_where}) names include directory "
    "'${_gdcontact_ode_includedir}', which has no ode/ode.h: a broken ODE installation")
endif()

# The version: <ode/version.h> (since 0.13) must agree with ode.pc's.
set(_gdcontact_ode_header_version "")
if(EXISTS "${_gdcontact_ode_header}/version.h")
  file(STRINGS "${_gdcontact_ode_header}/version.h" _line REGEX "define[ \t]+dODE_VERSION")
  string(REGEX MATCH "[0-9]+(\\.[0-9]+)+" _gdcontact_ode_header_version "${_line}")
endif()
if(NOT _gdcontact_ode_header_version)
  set(_gdcontact_ode_header_version "${ODE_VERSION}")
endif()
if(NOT _gdcontact_ode_header_version STREQUAL ODE_VERSION)
  message(FATAL_ERROR "gdcontact: ODE's ode.pc says version ${ODE_VERSION} but its headers "
    "(${_gdcontact_ode_header}/version.h) say ${_gdcontact_ode_header_version}: two ODEs mixed up")
endif()
if(ODE_VERSION VERSION_LESS 0.16.2)
  message(FATAL_ERROR "gdcontact needs ODE 0.16.2 or newer; found ODE ${ODE_VERSION} "
    "(${_gdcontact_ode_where}). Install a newer libode-dev or build ODE 0.16.x from its sources "
    "and point PKG_CONFIG_PATH (or CMAKE_PREFIX_PATH) at it.")
endif()
if(ODE_VERSION VERSION_GREATER_EQUAL 0.17)
  message(WARNING "gdcontact is checked with ODE 0.16.2 to 0.16.6; found ODE ${ODE_VERSION}")
endif()

# The precision, from the headers themselves (dReal is what the adapter converts from and to).
include(CheckCXXSourceCompiles)
include(CMakePushCheckState)
cmake_push_check_state(RESET)
set(CMAKE_REQUIRED_QUIET ON)
set(CMAKE_REQUIRED_INCLUDES ${ODE_INCLUDE_DIRS} ${_gdcontact_ode_includedir})
set(CMAKE_REQUIRED_DEFINITIONS ${ODE_CFLAGS_OTHER})
check_cxx_source_compiles("#include <ode/ode.h>
static_assert(sizeof(dReal) == sizeof(double), \"\");
int main() { return 0; }" GDCONTACT_ODE_IS_DOUBLE)
check_cxx_source_compiles("#include <ode/ode.h>
static_assert(sizeof(dReal) == sizeof(float), \"\");
int main() { return 0; }" GDCONTACT_ODE_IS_SINGLE)
cmake_pop_check_state()
if(GDCONTACT_ODE_IS_DOUBLE)
  set(GDCONTACT_ODE_PRECISION double)
elseif(GDCONTACT_ODE_IS_SINGLE)
  set(GDCONTACT_ODE_PRECISION single)
else()
  message(FATAL_ERROR "gdcontact: ODE's headers (${_gdcontact_ode_header}) do not compile with dReal "
    "as float or double (precision.h defines neither dSINGLE nor dDOUBLE?); gdcontact needs an ODE "
    "built in single or double precision")
endif()
# ode.pc records the precision ODE was built with; headers of another build would mismatch it.
if(_gdcontact_ode_pc_precision MATCHES "dSINGLE|dDOUBLE")
  if((_gdcontact_ode_pc_precision STREQUAL "dDOUBLE") AND NOT GDCONTACT_ODE_IS_DOUBLE
     OR (_gdcontact_ode_pc_precision STREQUAL "dSINGLE") AND NOT GDCONTACT_ODE_IS_SINGLE)
    message(FATAL_ERROR "gdcontact: ODE's ode.pc says precision=${_gdcontact_ode_pc_precision} but its "
      "headers (${_gdcontact_ode_header}) make dReal a ${GDCONTACT_ODE_PRECISION}: two ODEs mixed up")
  endif()
endif()

# Shared or static: what the library pkg-config resolved is.
set(_gdcontact_ode_kind "library not found")
foreach(_library IN LISTS ODE_LINK_LIBRARIES)
  if(_library MATCHES "libode[^/]*\\.(so|dylib)")
    set(_gdcontact_ode_kind "shared")
  elseif(_library MATCHES "libode[^/]*\\.a$")
    set(_gdcontact_ode_kind "static")
  endif()
endforeach()
if(_gdcontact_ode_kind STREQUAL "static")
  # A static libode needs what ode.pc lists as private (the C++ runtime, libm; libccd where ODE
  # was built against the system's): the --static flags, on the target every user links.
  set(_private ${ODE_STATIC_LIBRARIES})
  list(REMOVE_ITEM _private ode)
  foreach(_library IN LISTS _private)
    set_property(TARGET PkgConfig::ODE APPEND PROPERTY INTERFACE_LINK_LIBRARIES "-l${_library}")
  endforeach()
endif()

set(GDCONTACT_ODE_VERSION "${ODE_VERSION}")
if(GDCONTACT_ODE_PRECISION STREQUAL "double")  # as ode.pc's precision variable says it
  set(GDCONTACT_ODE_PC_PRECISION dDOUBLE)
else()
  set(GDCONTACT_ODE_PC_PRECISION dSINGLE)
endif()
message(STATUS "gdcontact: ODE ${ODE_VERSION} (${_gdcontact_ode_where}), ${GDCONTACT_ODE_PRECISION} "
  "precision, ${_gdcontact_ode_kind}, libccd: ${_gdcontact_ode_libccd}")
