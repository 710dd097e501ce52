# Every third-party dependency is found here, once, with only the components
# that the modules use. CMake/install-dependencies.sh installs the matching
# Debian packages.

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(embree 3 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 2 REQUIRED CONFIG)
find_package(ZLIB REQUIRED)
find_package(Threads REQUIRED)

find_package(VTK 9.1 REQUIRED COMPONENTS
  ChartsCore
  CommonColor
  CommonCore
  CommonDataModel
  CommonExecutionModel
  CommonMath
  CommonTransforms
  FiltersCore
  FiltersGeneral
  FiltersHybrid
  FiltersSources
  ImagingCore
  IOCore
  IOGeometry
  IOImage
  IOLegacy
  IOPLY
  IOXML
  IOXMLParser
  RenderingContext2D
  RenderingAnnotation
  RenderingContextOpenGL2
  RenderingCore
  RenderingFreeType
  RenderingOpenGL2
  ViewsContext2D)

find_package(ITK 5.2 REQUIRED COMPONENTS
  ITKBinaryMathematicalMorphology
  ITKCommon
  ITKConnectedComponents
  ITKDisplacementField
  ITKDistanceMap
  ITKImageFunction
  ITKImageGrid
  ITKImageIntensity
  ITKIOImageBase
  ITKGDCM
  ITKIOGDCM
  ITKIOMeta
  ITKIONIFTI
  ITKIONRRD
  ITKIOTransformBase
  ITKIOTransformHDF5
  ITKIOTransformInsightLegacy
  ITKIOTransformMatlab
  ITKLabelMap
  ITKMathematicalMorphology
  ITKMetricsv4
  ITKOptimizersv4
  ITKRegistrationMethodsv4
  ITKSmoothing
  ITKThresholding
  ITKTransform)

# aruco (OpenCV's contributed modules, libopencv-contrib-dev): ChArUco boards for calibration.
find_package(OpenCV 4.6 REQUIRED COMPONENTS core imgproc imgcodecs videoio video features2d calib3d aruco)

# Python wrapping (VIMLOP_WRAP_PYTHON) uses VTK's own wrapping tools and
# extends VTK's Python package, so it needs the interpreter that package
# belongs to: Debian's python3-vtk9 lives in /usr/lib/python3/dist-packages,
# for /usr/bin/python3, which may not be the first python3 on the PATH.
if(VIMLOP_WRAP_PYTHON)
  if(NOT VTK_WRAP_PYTHON)
    message(FATAL_ERROR "VIMLOP_WRAP_PYTHON: the VTK in ${VTK_DIR} was built without Python "
      "wrapping; install python3-vtk9 or configure with -DVIMLOP_WRAP_PYTHON=OFF")
  endif()
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS "${VTK_PREFIX_PATH}/bin/python3")
    set(Python3_EXECUTABLE "${VTK_PREFIX_PATH}/bin/python3" CACHE FILEPATH
      "The Python interpreter whose VTK package VIMLOP's Python modules extend")
  endif()
  find_package(VTK 9.1 REQUIRED COMPONENTS Python WrappingPythonCore)
  execute_process(COMMAND "${Python3_EXECUTABLE}" -c "import vtkmodules.vtkCommonExecutionModel"
    RESULT_VARIABLE vimlop_vtk_import_result OUTPUT_QUIET ERROR_VARIABLE vimlop_vtk_import_error)
  if(NOT vimlop_vtk_import_result EQUAL 0)
    string(STRIP "${vimlop_vtk_import_error}" vimlop_vtk_import_error)
    string(REGEX REPLACE ".*\n" "" vimlop_vtk_import_error "${vimlop_vtk_import_error}")
    message(FATAL_ERROR "VIMLOP_WRAP_PYTHON: ${Python3_EXECUTABLE} cannot import VTK's Python "
      "modules (${vimlop_vtk_import_error}); install python3-vtk9, set Python3_EXECUTABLE to the "
      "interpreter VTK was wrapped for, or configure with -DVIMLOP_WRAP_PYTHON=OFF")
  endif()
  message(STATUS "VIMLOP: Python wrapping for ${Python3_EXECUTABLE} (Python ${Python3_VERSION})")
endif()

# OpenIGTLink (Debian's libopenigtlink-dev has no imported target: plain variables).
find_package(OpenIGTLink REQUIRED NO_MODULE PATHS /usr/lib/openigtlink)

# Open3D (Debian's libopen3d-dev) is a peer in the evaluation protocols, not a
# dependency of the library: without it, the Open3D methods are unavailable.
find_package(Open3D QUIET)

if(BUILD_TESTING)
  find_package(GTest 1.10 REQUIRED)
endif()
