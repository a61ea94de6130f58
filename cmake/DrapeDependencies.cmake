# Third-party dependencies, all from Debian 12 packages (see scripts/setup.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Threads REQUIRED)
find_package(Ceres 2.1 REQUIRED)
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(assimp REQUIRED)
find_package(DrapeOpenCV REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TBB REQUIRED)          # libcloth: parallel assembly
find_package(CGAL 5.5 REQUIRED)     # libgarment: pattern triangulation (header-only + GMP/MPFR)
find_package(embree 3 REQUIRED)     # app layer: ray-traced renders
if(DRAPE_BUILD_TESTS)
  find_package(Catch2 2.13 REQUIRED)
endif()
