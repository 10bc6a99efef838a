# Locate the LAMMPS source headers matching the installed liblammps (Debian installs only the
# public ones). tools/setup/fetch-lammps-headers.sh extracts them from Debian's source package
# into a cache directory; nothing from LAMMPS lives in this repository.
#
# Out: TAPMC_LAMMPS_SOURCE_INCLUDE (directory with the full src/*.h and fmt/), and
#      LAMMPS_VERSION_NUMERIC (e.g. 20210929) for lammps_compat.h.

string(REGEX REPLACE "^([0-9]+).*" "\\1" LAMMPS_VERSION_NUMERIC "${LAMMPS_VERSION}")
if(NOT LAMMPS_VERSION_NUMERIC)
  message(FATAL_ERROR "TAPMC: could not read the LAMMPS version from LAMMPSConfigVersion.cmake")
endif()

if(DEFINED ENV{XDG_CACHE_HOME})
  set(_tapmc_cache "$ENV{XDG_CACHE_HOME}/tapmc")
else()
  set(_tapmc_cache "$ENV{HOME}/.cache/tapmc")
endif()
set(TAPMC_LAMMPS_HEADERS_DIR "${_tapmc_cache}/lammps-${LAMMPS_VERSION_NUMERIC}" CACHE PATH
    "Directory holding src/ headers of the installed LAMMPS version")

if(NOT EXISTS "${TAPMC_LAMMPS_HEADERS_DIR}/src/neigh_request.h")
  message(STATUS "TAPMC: fetching LAMMPS ${LAMMPS_VERSION_NUMERIC} headers into ${TAPMC_LAMMPS_HEADERS_DIR}")
  execute_process(
    COMMAND bash ${CMAKE_SOURCE_DIR}/tools/setup/fetch-lammps-headers.sh ${TAPMC_LAMMPS_HEADERS_DIR}
    RESULT_VARIABLE _tapmc_fetch_rc)
  if(NOT _tapmc_fetch_rc EQUAL 0 OR NOT EXISTS "${TAPMC_LAMMPS_HEADERS_DIR}/src/neigh_request.h")
    message(FATAL_ERROR "TAPMC: the LAMMPS source headers are missing and could not be fetched; "
            "run tools/setup/fetch-lammps-headers.sh ${TAPMC_LAMMPS_HEADERS_DIR} by hand")
  endif()
endif()
set(TAPMC_LAMMPS_SOURCE_INCLUDE "${TAPMC_LAMMPS_HEADERS_DIR}/src")
