# Finds only the OpenCV modules Drape uses (core, imgproc, imgcodecs) from Debian's
# per-module -dev packages, which ship no OpenCVConfig.cmake (that comes with the
# all-modules libopencv-dev, which we do not install). Defines imported targets
# DrapeOpenCV::core, DrapeOpenCV::imgproc, DrapeOpenCV::imgcodecs.
find_path(DrapeOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_drape_cv_libs)
foreach(_m core imgproc imgcodecs)
  find_library(DrapeOpenCV_${_m}_LIBRARY opencv_${_m})
  list(APPEND _drape_cv_libs DrapeOpenCV_${_m}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(DrapeOpenCV REQUIRED_VARS DrapeOpenCV_INCLUDE_DIR ${_drape_cv_libs})
if(DrapeOpenCV_FOUND)
  foreach(_m core imgproc imgcodecs)
    if(NOT TARGET DrapeOpenCV::${_m})
      add_library(DrapeOpenCV::${_m} UNKNOWN IMPORTED)
      set_target_properties(DrapeOpenCV::${_m} PROPERTIES
        IMPORTED_LOCATION "${DrapeOpenCV_${_m}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${DrapeOpenCV_INCLUDE_DIR}")
    endif()
  endforeach()
  set_property(TARGET DrapeOpenCV::imgproc PROPERTY INTERFACE_LINK_LIBRARIES DrapeOpenCV::core)
  set_property(TARGET DrapeOpenCV::imgcodecs PROPERTY INTERFACE_LINK_LIBRARIES DrapeOpenCV::imgproc)
endif()
