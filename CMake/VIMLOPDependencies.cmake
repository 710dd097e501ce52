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
  ITKIOGDCM
  ITKIOMeta
  ITKIONIFTI
  ITKIONRRD
  ITKLabelMap
  ITKMathematicalMorphology
  ITKMetricsv4
  ITKOptimizersv4
  ITKRegistrationMethodsv4
  ITKSmoothing
  ITKThresholding
  ITKTransform)

find_package(OpenCV 4.6 REQUIRED COMPONENTS core imgproc imgcodecs videoio features2d calib3d)

# OpenIGTLink (Debian's libopenigtlink-dev has no imported target: plain variables).
find_package(OpenIGTLink REQUIRED NO_MODULE PATHS /usr/lib/openigtlink)

# Open3D (Debian's libopen3d-dev) is a peer in the evaluation protocols, not a
# dependency of the library: without it, the Open3D methods are unavailable.
find_package(Open3D QUIET)

if(BUILD_TESTING)
  find_package(GTest 1.10 REQUIRED)
endif()
