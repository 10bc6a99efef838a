# Locate the LAMMPS source headers matching the LAMMPS in LAMMPS_DIR: TAPMC compiles against
# headers that a LAMMPS install does not include (src/*.h, src/fmt/). Nothing from LAMMPS lives
# in this repository.
#
# In:  TAPMC_LAMMPS_HEADERS_DIR, the top directory of a LAMMPS source tree of the same version
#      (the one with src/ and cmake/). Given by the user, it is only read: never fetched into,
#      never deleted. Not given, it is TAPMC's cache directory ~/.cache/tapmc/lammps-<version>
#      (or under $XDG_CACHE_HOME), where tools/setup/build-lammps-plugin.sh leaves the headers of
#      the LAMMPS it builds; only when LAMMPS_DIR belongs to Debian's packaged LAMMPS
#      (dpkg-query -S, if dpkg-query is on PATH) and the headers are not there yet does CMake
#      fetch them, with tools/setup/fetch-lammps-headers.sh (apt-get source, network, no root).
#      Any other case stops with a message naming TAPMC_LAMMPS_HEADERS_DIR: configuring against
#      a LAMMPS of one's own needs no apt, dpkg or root.
# Out: TAPMC_LAMMPS_SOURCE_INCLUDE (directory with the full src/*.h and fmt/), and
#      LAMMPS_VERSION_NUMERIC (e.g. 20210929) for lammps_compat.h.

# LAMMPSConfigVersion.cmake says 20210929 up to 2022 and 2026.7.4.0 in newer versions.
if(LAMMPS_VERSION MATCHES "^([0-9][0-9][0-9][0-9])\\.([0-9]+)\\.([0-9]+)")
  math(EXPR LAMMPS_VERSION_NUMERIC
       "${CMAKE_MATCH_1} * 10000 + ${CMAKE_MATCH_2} * 100 + ${CMAKE_MATCH_3}")
elseif(LAMMPS_VERSION MATCHES "^([0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9])")
  set(LAMMPS_VERSION_NUMERIC "${CMAKE_MATCH_1}")
else()
  message(FATAL_ERROR "TAPMC: LAMMPSConfigVersion.cmake gives the LAMMPS version as "
          "'${LAMMPS_VERSION}', neither 20210929 nor 2026.7.4 style; is LAMMPS_DIR a LAMMPS "
          "install (<prefix>/lib/cmake/LAMMPS)?")
endif()

# The version of the headers in DIR/src/version.h ('#define LAMMPS_VERSION "4 Jul 2026"') as
# 20260704, or 0 when unreadable.
function(tapmc_header_version dir out)
  set(_numeric 0)
  if(EXISTS "${dir}/src/version.h")
    file(STRINGS "${dir}/src/version.h" _line REGEX "define LAMMPS_VERSION ")
    if(_line MATCHES "\"([0-9]+) ([A-Za-z][a-z][a-z])[a-z]* ([0-9][0-9][0-9][0-9])\"")
      set(_months Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec)
      list(FIND _months "${CMAKE_MATCH_2}" _month)
      if(_month GREATER_EQUAL 0)
        math(EXPR _numeric "${CMAKE_MATCH_3} * 10000 + (${_month} + 1) * 100 + ${CMAKE_MATCH_1}")
      endif()
    endif()
  endif()
  set(${out} ${_numeric} PARENT_SCOPE)
endfunction()

if(DEFINED ENV{XDG_CACHE_HOME})
  set(_tapmc_cache "$ENV{XDG_CACHE_HOME}/tapmc")
else()
  set(_tapmc_cache "$ENV{HOME}/.cache/tapmc")
endif()
set(_tapmc_default_headers "${_tapmc_cache}/lammps-${LAMMPS_VERSION_NUMERIC}")
# Any LAMMPS source tree of the same version will do (a user's own checkout: its top directory).
set(TAPMC_LAMMPS_HEADERS_DIR "${_tapmc_default_headers}" CACHE PATH
    "Top directory of a LAMMPS source tree (with src/) of the version in LAMMPS_DIR")
get_filename_component(_tapmc_headers_dir "${TAPMC_LAMMPS_HEADERS_DIR}" ABSOLUTE)
get_filename_component(_tapmc_default_headers "${_tapmc_default_headers}" ABSOLUTE)
set(_tapmc_own_headers_dir TRUE)
if(_tapmc_headers_dir STREQUAL _tapmc_default_headers)
  set(_tapmc_own_headers_dir FALSE)  # TAPMC's cache directory: the fetch may fill it
endif()
string(CONCAT _tapmc_headers_option
       "-DTAPMC_LAMMPS_HEADERS_DIR=<the top directory of the LAMMPS source tree that the "
       "LAMMPS in LAMMPS_DIR was built from: the directory with src/ and cmake/; any unpacked "
       "source of LAMMPS version ${LAMMPS_VERSION_NUMERIC} will do, it need not be built>. "
       "See doc/install.rst, route 1.")
set(_tapmc_what_to_give "Give ${_tapmc_headers_option}")
# Debian's LAMMPS without network: route 2's own section, not route 1 (your own LAMMPS)
string(REPLACE "See doc/install.rst, route 1."
       "See doc/install.rst, route 2, 'Without network'." _tapmc_offline_option
       "${_tapmc_headers_option}")

if(NOT EXISTS "${_tapmc_headers_dir}/src/neigh_request.h")
  if(_tapmc_own_headers_dir)
    # The user's directory: read, never written to.
    if(EXISTS "${_tapmc_headers_dir}/neigh_request.h")
      set(_tapmc_hint "It looks like the src/ directory of a LAMMPS tree: give its parent. ")
    else()
      set(_tapmc_hint "")
    endif()
    message(FATAL_ERROR "TAPMC: TAPMC_LAMMPS_HEADERS_DIR = ${TAPMC_LAMMPS_HEADERS_DIR} has no "
            "src/neigh_request.h, so it is not a LAMMPS source tree. ${_tapmc_hint}"
            "${_tapmc_what_to_give}")
  endif()
  # Fetch only for Debian's packaged LAMMPS: the fetch takes Debian's source package of the
  # installed liblammps (tools/setup/fetch-lammps-headers.sh).
  get_filename_component(_tapmc_lammps_config "${LAMMPS_DIR}/LAMMPSConfig.cmake" REALPATH)
  execute_process(COMMAND dpkg-query -S "${_tapmc_lammps_config}"
                  RESULT_VARIABLE _tapmc_dpkg_rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT _tapmc_dpkg_rc STREQUAL "0")
    message(FATAL_ERROR "TAPMC: the LAMMPS source headers are missing: TAPMC compiles against "
            "LAMMPS headers that a LAMMPS install does not include (src/*.h, src/fmt/), and "
            "TAPMC_LAMMPS_HEADERS_DIR was not given (TAPMC's cache directory "
            "${TAPMC_LAMMPS_HEADERS_DIR}, where tools/setup/build-lammps-plugin.sh leaves the "
            "headers of the LAMMPS it builds, has none). ${_tapmc_what_to_give}")
  endif()
  message(STATUS "TAPMC: fetching LAMMPS ${LAMMPS_VERSION_NUMERIC} headers from Debian's source package into ${TAPMC_LAMMPS_HEADERS_DIR}")
  execute_process(
    COMMAND bash ${CMAKE_SOURCE_DIR}/tools/setup/fetch-lammps-headers.sh ${_tapmc_headers_dir}
    RESULT_VARIABLE _tapmc_fetch_rc)
  if(NOT _tapmc_fetch_rc EQUAL 0 OR NOT EXISTS "${_tapmc_headers_dir}/src/neigh_request.h")
    message(FATAL_ERROR "TAPMC: the LAMMPS source headers are missing and could not be fetched "
            "from Debian's source package (why: above); run tools/setup/fetch-lammps-headers.sh "
            "${TAPMC_LAMMPS_HEADERS_DIR} by hand once that is mended, or, offline, give "
            "${_tapmc_offline_option}")
  endif()
  tapmc_header_version("${_tapmc_headers_dir}" _tapmc_fetched)
  if(NOT _tapmc_fetched EQUAL LAMMPS_VERSION_NUMERIC)
    # Debian's source package is of another version than the LAMMPS in LAMMPS_DIR: useless.
    # (TAPMC's own cache directory only.)
    file(REMOVE_RECURSE "${_tapmc_headers_dir}")
  endif()
endif()
tapmc_header_version("${_tapmc_headers_dir}" _tapmc_headers)
if(NOT _tapmc_headers EQUAL LAMMPS_VERSION_NUMERIC)
  if(_tapmc_headers EQUAL 0)
    set(_tapmc_headers "of unknown version (no readable src/version.h)")
  else()
    set(_tapmc_headers "version ${_tapmc_headers}")
  endif()
  message(FATAL_ERROR "TAPMC: the LAMMPS in ${LAMMPS_DIR} is version ${LAMMPS_VERSION_NUMERIC} "
          "but the source headers in TAPMC_LAMMPS_HEADERS_DIR = ${TAPMC_LAMMPS_HEADERS_DIR} "
          "are ${_tapmc_headers}. ${_tapmc_what_to_give}")
endif()
set(TAPMC_LAMMPS_SOURCE_INCLUDE "${_tapmc_headers_dir}/src")
