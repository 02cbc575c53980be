# SuiteSparse 5.12 on Debian ships no CMake config for CHOLMOD and UMFPACK: find them by hand.
# Defines the imported target SuiteSparse::SuiteSparse (CHOLMOD, UMFPACK and their helpers).
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
foreach(lib cholmod umfpack amd colamd camd ccolamd suitesparseconfig)
  find_library(SuiteSparse_${lib}_LIBRARY NAMES ${lib})
  list(APPEND SuiteSparse_LIBRARIES ${SuiteSparse_${lib}_LIBRARY})
  list(APPEND _ss_required SuiteSparse_${lib}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS SuiteSparse_INCLUDE_DIR ${_ss_required})
if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::SuiteSparse)
  add_library(SuiteSparse::SuiteSparse INTERFACE IMPORTED)
  set_target_properties(SuiteSparse::SuiteSparse PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SuiteSparse_LIBRARIES}")
endif()
