#ifndef vimlop_Testing_OptionLayout_h
#define vimlop_Testing_OptionLayout_h

#include <vimlop/Core/LevenbergMarquardtPoseEstimator.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/PoseUpdate.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/SyntheticExperiment.h>

#include <cstddef>

/**
 * The sizes, alignments and member offsets of Core's public option and value
 * structs: X(name, value) for each. A navigation program built with other
 * flags than the library (e.g. -mavx2) must see the same layout, or it
 * writes options where the library does not read them.
 */
#define VIMLOP_OPTION_LAYOUT(X)                                                                    \
  X("sizeof RegistrationOptions", sizeof(vimlop::RegistrationOptions))                             \
  X("alignof RegistrationOptions", alignof(vimlop::RegistrationOptions))                           \
  X("offsetof RegistrationOptions::contourMatch",                                                  \
    offsetof(vimlop::RegistrationOptions, contourMatch))                                           \
  X("offsetof RegistrationOptions::minScale", offsetof(vimlop::RegistrationOptions, minScale))     \
  X("offsetof RegistrationOptions::poseUpdate", offsetof(vimlop::RegistrationOptions, poseUpdate)) \
  X("offsetof RegistrationOptions::threads", offsetof(vimlop::RegistrationOptions, threads))       \
  X("sizeof MultiStartOptions", sizeof(vimlop::MultiStartOptions))                                 \
  X("offsetof MultiStartOptions::failureContourErrorPx",                                           \
    offsetof(vimlop::MultiStartOptions, failureContourErrorPx))                                    \
  X("offsetof MultiStartOptions::failureResidualErrorMm",                                          \
    offsetof(vimlop::MultiStartOptions, failureResidualErrorMm))                                   \
  X("sizeof PoseUpdateProblem", sizeof(vimlop::PoseUpdateProblem))                                 \
  X("offsetof PoseUpdateProblem::kappa", offsetof(vimlop::PoseUpdateProblem, kappa))               \
  X("sizeof ContourPair", sizeof(vimlop::ContourPair))                                             \
  X("sizeof SyntheticOptions", sizeof(vimlop::SyntheticOptions))                                   \
  X("sizeof PinholeCamera", sizeof(vimlop::PinholeCamera))                                         \
  X("sizeof CameraPose", sizeof(vimlop::CameraPose))                                               \
  X("sizeof SimilarityTransform", sizeof(vimlop::SimilarityTransform))                             \
  X("sizeof RegistrationResult", sizeof(vimlop::RegistrationResult))                               \
  X("sizeof LevenbergMarquardtPoseEstimator", sizeof(vimlop::LevenbergMarquardtPoseEstimator))

namespace fixtures
{

/// The values of VIMLOP_OPTION_LAYOUT as a translation unit built with
/// -mavx2 sees them (OptionLayoutAvx2.cxx; without -mavx2 where the compiler
/// has no such flag). Plain data: nothing there runs AVX2 instructions.
const std::size_t* optionLayoutWithAvx2(int& count);

} // namespace fixtures

#endif
