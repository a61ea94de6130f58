# Third-party dependencies, all from Debian 12 packages (see scripts/setup.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Threads REQUIRED)
find_package(Ceres 2.1 REQUIRED)
# Debian's Ceres and SuiteSparse targets name ATLAS's own libraries (libf77blas, libatlas)
# besides the generic libblas/liblapack. Linked directly, libf77blas would provide dgemm_
# & co. to the whole process ahead of the system's libblas.so.3 (update-alternatives; serial
# OpenBLAS from scripts/setup.sh). Drop the ATLAS-specific names: the generic ones remain.
foreach(_drape_target Ceres::ceres BLAS::BLAS LAPACK::LAPACK SuiteSparse::Config SuiteSparse::CHOLMOD
                      SuiteSparse::SPQR)
  if(TARGET ${_drape_target})
    get_target_property(_drape_libs ${_drape_target} INTERFACE_LINK_LIBRARIES)
    if(_drape_libs)
      list(FILTER _drape_libs EXCLUDE REGEX "lib(f77blas|atlas)\\.so")
      set_target_properties(${_drape_target} PROPERTIES INTERFACE_LINK_LIBRARIES "${_drape_libs}")
    endif()
  endif()
endforeach()
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(assimp REQUIRED)
find_package(DrapeOpenCV REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TBB REQUIRED)          # libcloth: parallel assembly
find_package(Pagmo REQUIRED)        # libgarment: particle swarm search of the sizing (pagmo2)
find_package(CGAL 5.5 REQUIRED)     # libgarment: pattern triangulation (header-only + GMP/MPFR)
find_package(embree 3 REQUIRED)     # app layer: ray-traced renders
if(DRAPE_BUILD_TESTS)
  find_package(Catch2 2.13 REQUIRED)
endif()
