# libRmath through pkg-config as the imported target PkgConfig::RMATH, for
# libmcstat's build and for mcstatConfig.cmake.  Debian's libRmath.pc (package
# r-mathlib) names includedir=/usr/share/R/include, which only R itself
# (r-base-core) creates; Rmath.h is in /usr/include.  CMake refuses an
# imported target whose include directory does not exist, so the directories
# that do not are dropped, and Rmath.h must then be found on the compiler's
# own path.
find_package(PkgConfig REQUIRED)
if(NOT TARGET PkgConfig::RMATH)
  pkg_check_modules(RMATH REQUIRED IMPORTED_TARGET libRmath)
  get_target_property(_mcstat_rmath_inc PkgConfig::RMATH INTERFACE_INCLUDE_DIRECTORIES)
  set(_mcstat_rmath_keep)
  foreach(_d IN LISTS _mcstat_rmath_inc)
    if(EXISTS "${_d}")
      list(APPEND _mcstat_rmath_keep "${_d}")
    endif()
  endforeach()
  find_path(MCSTAT_RMATH_H_DIR Rmath.h HINTS ${_mcstat_rmath_keep})
  if(NOT MCSTAT_RMATH_H_DIR)
    message(FATAL_ERROR "libRmath: pkg-config found the library but not Rmath.h "
      "(Debian: apt-get install --no-install-recommends r-mathlib)")
  endif()
  set_property(TARGET PkgConfig::RMATH PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${_mcstat_rmath_keep}")
endif()
