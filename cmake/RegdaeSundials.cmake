# Find SUNDIALS (>= 6.4) with its Fortran 2003 interface to IDA, and repair
# Debian's package config: it gives the imported Fortran targets the include
# directory <prefix>/fortran, which does not exist (the .mod files are in
# <prefix>/include/sundials/fortran), so CMake refuses to generate.
#
# Result: the imported targets SUNDIALS::fida_mod_shared and the Fortran modules of
# the band and sparse (KLU) matrices and linear solvers, usable as is, and the
# cache variable REGDAE_SUNDIALS_FORTRAN_MODULE_DIR.
if(TARGET SUNDIALS::fida_mod_shared AND REGDAE_SUNDIALS_FORTRAN_MODULE_DIR)
  return()
endif()

find_package(SUNDIALS 6.4 REQUIRED CONFIG)

get_target_property(_regdae_sundials_inc SUNDIALS::ida_shared INTERFACE_INCLUDE_DIRECTORIES)
find_path(REGDAE_SUNDIALS_FORTRAN_MODULE_DIR
  NAMES fida_mod.mod
  HINTS ${_regdae_sundials_inc}/sundials/fortran ${SUNDIALS_DIR}/../../../../include/sundials/fortran
  PATHS /usr/include/sundials/fortran /usr/local/include/sundials/fortran
  DOC "Directory holding SUNDIALS' Fortran module files (fida_mod.mod)")
if(NOT REGDAE_SUNDIALS_FORTRAN_MODULE_DIR)
  message(FATAL_ERROR "regdae: fida_mod.mod not found; install libsundials-fortran-dev or set "
                      "REGDAE_SUNDIALS_FORTRAN_MODULE_DIR")
endif()

foreach(_regdae_target IN ITEMS SUNDIALS::fida_mod_shared SUNDIALS::fcvode_mod_shared
                              SUNDIALS::fsunmatrixband_mod_shared SUNDIALS::fsunlinsolband_mod_shared
                              SUNDIALS::fsunmatrixsparse_mod_shared SUNDIALS::fsunlinsolklu_mod_shared)
  if(TARGET ${_regdae_target})
    set_target_properties(${_regdae_target} PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${_regdae_sundials_inc};${REGDAE_SUNDIALS_FORTRAN_MODULE_DIR}")
  endif()
endforeach()
unset(_regdae_target)
unset(_regdae_sundials_inc)
