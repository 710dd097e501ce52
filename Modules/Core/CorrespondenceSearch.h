#ifndef vimlop_CorrespondenceSearch_h
#define vimlop_CorrespondenceSearch_h

#include <vimlop/Core/Correspondences.h>
#include <vimlop/Core/MethodDescriptor.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

class TaskPool;

/**
 * @brief Matches the data to the model at an estimate T and marks the
 * outliers: 3-D matches (V2), visible model contours (V3, V4), oriented 2-D
 * matches (V5), then the outlier tests (V8), as the method's descriptor says.
 *
 * It is a class, not a function, for what it keeps between estimates: the
 * point covariances scaled for equal influence (V9), the chi-square quantile,
 * and each point's last matched face, which warm-starts its next search (the
 * matches do not depend on it, only the search time). Model, data, options and
 * pool must outlive it.
 */
class CorrespondenceSearch
{
public:
  CorrespondenceSearch(const RegistrationModel& model, const RegistrationData& data,
    const RegistrationOptions& options, TaskPool& pool);

  /**
   * @brief The matches at `sfmToCT`.
   * @param withContours match the frames' contours too (V3-V5); else the
   *   frames' entries stay empty
   * @param trim trim the fraction RegistrationOptions::trimFraction of 3-D
   *   pairs before the chi-square test
   */
  Correspondences find(const SimilarityTransform& sfmToCT, bool withContours, bool trim);

  /// @brief Σ_i scaled by n3d (1 - p_t) / n2d when the method uses contours
  /// and RegistrationOptions::equalInfluence is on (V9), else Σ_i (mm², SfM axes).
  const std::vector<Eigen::Matrix3d>& covariances() const { return this->Covariances; }

private:
  void matchFrame(const SimilarityTransform& sfmToCT, int j, FrameCorrespondences& out) const;
  void rejectOutliers(
    const SimilarityTransform& sfmToCT, bool withContours, bool trim, Correspondences& c) const;

  const RegistrationModel& Model;
  const RegistrationData& Data;
  const RegistrationOptions Options; // a copy: callers may pass a temporary
  TaskPool& Pool;
  MethodDescriptor Method;
  std::vector<Eigen::Matrix3d> Covariances;
  std::vector<int> Hints;
  double ChiSquare3 = 0.0;
};

} // namespace vimlop

#endif
