# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# CMake package of an installed TAPMC (cmake --install BUILD --prefix P): in a downstream project,
#   find_package(TAPMC 0.1 REQUIRED)     # with -DCMAKE_PREFIX_PATH=P
#   target_link_libraries(myprog PRIVATE TAPMC::tapmc)
# TAPMC::tapmc is P/lib/libtapmc.so with P/include/tapmc (register_styles.h: tapmc_register(lmp)
# adds the TAPMC styles to a LAMMPS instance). The library is linked with the LAMMPS it was built
# against (Debian's liblammps.so.0 unless -DLAMMPS_DIR said otherwise); use that LAMMPS too.
# TAPMC_LMP_EXECUTABLE is P/bin/lmp_tapmc.
get_filename_component(_tapmc_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
if(NOT EXISTS "${_tapmc_prefix}/lib/libtapmc.so")
  set(TAPMC_FOUND FALSE)
  set(TAPMC_NOT_FOUND_MESSAGE "${_tapmc_prefix}/lib/libtapmc.so is missing")
  return()
endif()
if(NOT TARGET TAPMC::tapmc)
  add_library(TAPMC::tapmc SHARED IMPORTED)
  set_target_properties(TAPMC::tapmc PROPERTIES
    IMPORTED_LOCATION "${_tapmc_prefix}/lib/libtapmc.so"
    IMPORTED_SONAME "libtapmc.so"
    INTERFACE_INCLUDE_DIRECTORIES "${_tapmc_prefix}/include/tapmc")
endif()
set(TAPMC_LMP_EXECUTABLE "${_tapmc_prefix}/bin/lmp_tapmc")
unset(_tapmc_prefix)
