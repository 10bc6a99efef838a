# Locate the LAMMPS source headers matching the installed liblammps (Debian installs only the
# public ones). tools/setup/fetch-lammps-headers.sh extracts them from Debian's source package
# into a cache directory; nothing from LAMMPS lives in this repository.
#
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
# Any LAMMPS source tree of the same version will do (a user's own checkout: its top directory).
set(TAPMC_LAMMPS_HEADERS_DIR "${_tapmc_cache}/lammps-${LAMMPS_VERSION_NUMERIC}" CACHE PATH
    "Directory holding src/ headers of the LAMMPS version in LAMMPS_DIR (a LAMMPS source tree)")

if(NOT EXISTS "${TAPMC_LAMMPS_HEADERS_DIR}/src/neigh_request.h")
  # The fetch takes Debian's source package of the installed liblammps (or
  # TAPMC_LAMMPS_SRC_VERSION); tools/setup/build-lammps-plugin.sh leaves the headers of the
  # version it builds here itself.
  message(STATUS "TAPMC: fetching LAMMPS ${LAMMPS_VERSION_NUMERIC} headers into ${TAPMC_LAMMPS_HEADERS_DIR}")
  execute_process(
    COMMAND bash ${CMAKE_SOURCE_DIR}/tools/setup/fetch-lammps-headers.sh ${TAPMC_LAMMPS_HEADERS_DIR}
    RESULT_VARIABLE _tapmc_fetch_rc)
  if(NOT _tapmc_fetch_rc EQUAL 0 OR NOT EXISTS "${TAPMC_LAMMPS_HEADERS_DIR}/src/neigh_request.h")
    message(FATAL_ERROR "TAPMC: the LAMMPS source headers are missing and could not be fetched; "
            "run tools/setup/fetch-lammps-headers.sh ${TAPMC_LAMMPS_HEADERS_DIR} by hand, or "
            "give -DTAPMC_LAMMPS_HEADERS_DIR=<LAMMPS source tree of version "
            "${LAMMPS_VERSION_NUMERIC}>")
  endif()
  tapmc_header_version("${TAPMC_LAMMPS_HEADERS_DIR}" _tapmc_fetched)
  if(NOT _tapmc_fetched EQUAL LAMMPS_VERSION_NUMERIC)
    # Debian's source package is of another version than the LAMMPS in LAMMPS_DIR: useless.
    file(REMOVE_RECURSE "${TAPMC_LAMMPS_HEADERS_DIR}")
  endif()
endif()
tapmc_header_version("${TAPMC_LAMMPS_HEADERS_DIR}" _tapmc_headers)
if(NOT _tapmc_headers EQUAL LAMMPS_VERSION_NUMERIC)
  if(_tapmc_headers EQUAL 0)
    set(_tapmc_headers "of unknown version (no readable src/version.h)")
  else()
    set(_tapmc_headers "version ${_tapmc_headers}")
  endif()
  message(FATAL_ERROR "TAPMC: the LAMMPS in ${LAMMPS_DIR} is version ${LAMMPS_VERSION_NUMERIC} "
          "but the source headers in ${TAPMC_LAMMPS_HEADERS_DIR} are ${_tapmc_headers}. "
          "Give -DTAPMC_LAMMPS_HEADERS_DIR=<the LAMMPS source "
          "tree that LAMMPS was built from>; tools/setup/build-lammps-plugin.sh provides them "
          "for the LAMMPS it builds.")
endif()
set(TAPMC_LAMMPS_SOURCE_INCLUDE "${TAPMC_LAMMPS_HEADERS_DIR}/src")
