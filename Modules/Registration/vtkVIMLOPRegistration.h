#ifndef vtkVIMLOPRegistration_h
#define vtkVIMLOPRegistration_h

#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationOptionTable.h>
#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Registration/VTKOptionMacros.h>

#include "VIMLOPRegistrationModule.h"

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <memory>

class vtkAlgorithmOutput;
class vtkLinearTransform;
class vtkPolyData;
class vtkTable;
class vtkTransform;
class vtkTransformCollection;
class vtkVIMLOPDepthVisibility;

namespace vimlop
{
class RegistrationModel;
}

/**
 * @brief V-IMLOP as a VTK algorithm: registers video data (SfM points and
 * oriented video contours) to a CT model surface and offers the similarity
 * transform T (SfM frame to CT frame) as a live vtkLinearTransform.
 *
 * Inputs, one connection each (the layouts are in RegistrationInputConversion.h):
 * - port 0 (ModelPort), vtkPolyData: the model surface, CT frame, mm, normals
 *   into the air. Required. Without a "Normals" cell array the normals are
 *   computed, with a warning.
 * - port 1 (PointsPort), vtkPolyData: the SfM points, SfM frame, with an
 *   optional "Covariance" point array. Required.
 * - port 2 (FramesPort), vtkTable: the frames' intrinsics and SfM-frame poses.
 *   Required by V-IMLOP; optional for IMLP and trimmed ICP (without frames
 *   there is no camera to keep inside the airway).
 * - port 3 (ContoursPort), vtkPolyData: the video contour points of all
 *   frames, told apart by a "FrameId" point array. Required by V-IMLOP.
 *
 * Why four fixed ports and not a repeatable port or a multi-block: the four
 * inputs are of different kinds with different producers (a surface filter,
 * an SfM reader, a frame table, a contour detector), each is one data object
 * whatever the number of frames, and fixed ports let each come from its own
 * pipeline branch and re-execute alone. Frames are told apart by ids, not by
 * connections, so a frame table and contours that disagree are caught with a
 * clear message. All four ports are declared optional to the pipeline, so
 * that a missing connection is reported by this filter with what is missing
 * instead of by the executive.
 *
 * Outputs (layouts in RegistrationOutputConversion.h):
 * - port 0, vtkPolyData: the registered points, CT frame, with inlier flags;
 * - port 1, vtkTable: the camera pose of every frame in CT (FrameId, 4 x 4
 *   CameraToCT), its contour error and inlier counts;
 * - port 2, vtkPolyData: the matched model and video contour pairs.
 * GetTransform() is T = [s, R, t] with T(x) = s R x + t (SfM frame to CT
 * frame, mm): the same object for the filter's lifetime, updated in place
 * whenever the filter executes, so that actors (SetUserTransform) and
 * vtkTransformPolyDataFilter instances holding it follow every re-execution.
 *
 * The start of the registration is SetInitialTransform() (SfM to CT, a
 * similarity; identity when none). Its modification time counts as the
 * filter's: changing it re-executes the filter. Do not pass GetTransform()
 * itself (that would make the filter always out of date); copy its matrix
 * into a vtkTransform of your own to restart from a result.
 *
 * Several starts make a multi-start (V13): SetStarts() with a collection of
 * similarities, or SetStartFromCanonicalPoses() with the frames' middle
 * camera placed at canonical poses along the model's airway (at
 * InitialScale). Each start runs (times each scale factor, candidates in
 * parallel), the least contour error wins, and GetFlaggedAsFailure() says
 * whether the winner's contour error exceeds FailureThresholdPx or its 3-D
 * residual FailureResidualMm (a single start is flagged the same way). The
 * defaults of every option are Core's, the main job's
 * (vimlop::VideoRegistrationOptions holds the same ones for `vimlop
 * register` and Python's `vimlop.register_video`).
 *
 * Events: after every iteration that updates the estimate (vimlop's
 * iteration callback; the iterations that stop on a stall return to an
 * earlier estimate instead and are only in the result's history), one
 * vtkCommand::ProgressEvent (progress = iteration / MaxIterations; the
 * executive adds 0 before and 1 after) and one IterationEvent whose call data
 * is a `const vimlop::IterationRecord*` (valid during the callback: the
 * iteration's estimates, costs, inlier counts, errors and stage times). Setting
 * AbortExecute (e.g. from an observer) stops the registration after the
 * current iteration; the outputs then hold its last estimate and
 * GetTerminationReason() says Cancelled. Errors (missing inputs, bad data, a
 * camera starting outside the model) are reported through vtkErrorMacro and
 * fail the execution.
 *
 * RequestData only converts the inputs to Core's structs, calls
 * vimlop::registerVideo() and converts the result. The model's search
 * structures are kept between executions while the model input and the
 * visibility backend stay the same.
 */
class VIMLOPREGISTRATION_EXPORT vtkVIMLOPRegistration : public vtkAlgorithm
{
public:
  static vtkVIMLOPRegistration* New();
  vtkTypeMacro(vtkVIMLOPRegistration, vtkAlgorithm)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Input and output port numbers.
  enum Ports
  {
    ModelPort = 0,
    PointsPort = 1,
    FramesPort = 2,
    ContoursPort = 3,
    RegisteredPointsPort = 0,
    CameraPosesPort = 1,
    CorrespondencesPort = 2
  };

  /// The event fired after every iteration; call data: `const vimlop::IterationRecord*`.
  enum Events
  {
    IterationEvent = vtkCommand::UserEvent + 7811
  };

  /// Which backend decides contour visibility (V4).
  enum class VisibilityBackend
  {
    Embree, ///< ray-occlusion tests (the fast path; thread-safe)
    ZBuffer ///< the paper's offscreen z-buffer (vtkVIMLOPDepthVisibility; needs a display)
  };

  ///@{
  /// Connect the inputs (see the class description).
  void SetModelConnection(vtkAlgorithmOutput* output);
  void SetModelData(vtkPolyData* surface);
  void SetPointsConnection(vtkAlgorithmOutput* output);
  void SetPointsData(vtkPolyData* points);
  void SetFramesConnection(vtkAlgorithmOutput* output);
  void SetFramesData(vtkTable* frames);
  void SetContoursConnection(vtkAlgorithmOutput* output);
  void SetContoursData(vtkPolyData* contours);
  ///@}

  ///@{
  /// The outputs (see the class description); valid after Update().
  vtkPolyData* GetRegisteredPoints();
  vtkTable* GetCameraPoses();
  vtkPolyData* GetCorrespondences();
  ///@}

  /// The estimated transform T, SfM frame to CT frame (live: see the class description).
  vtkLinearTransform* GetTransform();

  ///@{
  /// Start of the registration, SfM frame to CT frame: a similarity (uniform
  /// scale, rotation, translation in mm). Default none: identity.
  void SetInitialTransform(vtkLinearTransform* transform);
  vtkLinearTransform* GetInitialTransform();
  ///@}

  ///@{
  /// Several starts, each a similarity from the SfM frame to the CT frame: a
  /// multi-start (see the class description) that replaces the initial
  /// transform when the collection is not empty. Default none. Modifying the
  /// collection's transforms does not re-execute the filter: call Modified().
  void SetStarts(vtkTransformCollection* starts);
  vtkTransformCollection* GetStarts();
  ///@}

  ///@{
  /// Start from canonical poses (V13 b): the middle frame placed at every
  /// pose vimlop::makeCanonicalPoses finds along the model's airway (default
  /// off). Needs the frame table and InitialScale.
  vtkSetMacro(StartFromCanonicalPoses, bool);
  vtkGetMacro(StartFromCanonicalPoses, bool);
  vtkBooleanMacro(StartFromCanonicalPoses, bool);
  ///@}

  ///@{
  /// Scale of the canonical starts, mm per SfM unit (e.g. from a tracker,
  /// V14; default 0: unset).
  vtkSetClampMacro(InitialScale, double, 0.0, 1e12);
  vtkGetMacro(InitialScale, double);
  ///@}

  ///@{
  /// V13: mean contour error above which a result is flagged as a failure, px (default 4).
  void SetFailureThresholdPx(double threshold);
  double GetFailureThresholdPx() const { return this->MultiStart.failureContourErrorPx; }
  ///@}

  ///@{
  /// V13: mean 3-D residual above which a result is flagged as a failure, mm (default 0.8).
  void SetFailureResidualMm(double threshold);
  double GetFailureResidualMm() const { return this->MultiStart.failureResidualErrorMm; }
  ///@}

  ///@{
  /// The algorithm (default V-IMLOP; IMLP and trimmed ICP are the baselines).
  void SetMethod(vimlop::RegistrationMethod method);
  vimlop::RegistrationMethod GetMethod() const { return this->Options.method; }
  void SetMethodToVIMLOP() { this->SetMethod(vimlop::RegistrationMethod::VIMLOP); }
  void SetMethodToIMLP() { this->SetMethod(vimlop::RegistrationMethod::IMLP); }
  void SetMethodToTrimmedICP() { this->SetMethod(vimlop::RegistrationMethod::TrimmedICP); }
  ///@}

  ///@{
  /// Contour visibility backend (default Embree).
  void SetVisibilityBackend(VisibilityBackend backend);
  VisibilityBackend GetVisibilityBackend() const { return this->Backend; }
  ///@}

  ///@{
  /// Isotropic std of the SfM points when the points carry no "Covariance"
  /// array, mm (default 0.5).
  vtkSetClampMacro(DefaultPointSigmaMm, double, 1e-6, 1e6);
  vtkGetMacro(DefaultPointSigmaMm, double);
  ///@}

  ///@{
  /// V5: covariance Σ2d of video contour positions, pixels² in image axes, as
  /// (σuu², σuv, σvv²) (default (1, 0, 1): the paper's value for video).
  void SetContourPositionCovariancePx2(double uu, double uv, double vv);
  void GetContourPositionCovariancePx2(double covariance[3]) const;
  ///@}

  ///@{
  /// V7: bounds on the scale s, SfM units to mm (defaults 0 and +infinity:
  /// unbounded). The initial transform's scale must lie within them.
  void SetMinScale(double scale);
  double GetMinScale() const { return this->Options.minScale; }
  void SetMaxScale(double scale);
  double GetMaxScale() const { return this->Options.maxScale; }
  ///@}

  ///@{
  /**
   * Every other setting of vimlop::RegistrationOptions, generated from
   * RegistrationOptionTable.h (the table gives each one's meaning, unit and
   * range; RegistrationOptions.h its default and why): numbers as
   * Set<Name>/Get<Name>, clamped into [Get<Name>MinValue(),
   * Get<Name>MaxValue()], e.g. SetContourKappa, SetTrimFraction,
   * SetMaxIterations, SetNumberOfThreads; switches as Set<Name>, <Name>On and
   * <Name>Off, e.g. AnatomicalConstraintOff(). The defaults are Core's, the
   * main job's.
   */
#define vtkVIMLOPRegistrationValue(Name, Type, member, key, flag, min, max, help)                  \
  vtkVIMLOPValueOptionMacro(this->Options.member, Name, Type, min, max)
#define vtkVIMLOPRegistrationSwitch(Name, member, key, flag, help)                                 \
  vtkVIMLOPSwitchOptionMacro(this->Options.member, Name)
  VIMLOP_REGISTRATION_VALUES(vtkVIMLOPRegistrationValue)
  VIMLOP_REGISTRATION_SWITCHES(vtkVIMLOPRegistrationSwitch)
#undef vtkVIMLOPRegistrationValue
#undef vtkVIMLOPRegistrationSwitch
  ///@}

  /// @brief Every option above as Core's struct (what RequestData passes on).
  const vimlop::RegistrationOptions& GetRegistrationOptions() const
  {
    return this->Options;
  }

  ///@{
  /// Outcome of the last execution.
  const vimlop::RegistrationResult& GetResult() const
  {
    return this->Result;
  }
  /// The data of the last execution, as converted from the inputs.
  const vimlop::RegistrationData& GetRegistrationData() const
  {
    return this->Data;
  }
  vimlop::TerminationReason GetTerminationReason() const
  {
    return this->Result.termination;
  }
  int GetNumberOfIterations() const
  {
    return this->Result.iterations;
  }
  ///@{
  /**
   * @brief The iteration an IterationEvent reports, for observers that cannot
   * read its call data (Python): its number, the scale of the estimate it
   * ended with and its mean contour error (px). GetTransform() changes only
   * when the execution ends; after it these hold the last iteration's.
   */
  int GetCurrentIteration() const
  {
    return this->Current.iteration;
  }
  double GetCurrentScale() const
  {
    return this->Current.updated.scale;
  }
  double GetCurrentContourErrorPx() const
  {
    return this->Current.contourErrorPx;
  }
  ///@}
  double GetResidualErrorMm() const
  {
    return this->Result.residualErrorMm;
  }
  double GetContourErrorPx() const
  {
    return this->Result.contourErrorPx;
  }
  /// V13: true when the result's contour error exceeds FailureThresholdPx, its
  /// 3-D residual FailureResidualMm, or too few video contour points matched:
  /// do not navigate with it.
  bool GetFlaggedAsFailure() const
  {
    return this->Outcome.failure;
  }
  /// Candidates of the last execution (1 for a single start) and the winner's index.
  int GetNumberOfCandidates() const
  {
    return static_cast<int>(this->Outcome.candidates.size());
  }
  int GetWinningCandidate() const
  {
    return this->Outcome.bestCandidate;
  }
  /// The multi-start's outcome (every candidate's start, errors and iterations).
  const vimlop::MultiStartResult& GetMultiStartResult() const
  {
    return this->Outcome;
  }
  ///@}

  vtkMTimeType GetMTime() override;

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkVIMLOPRegistration();
  ~vtkVIMLOPRegistration() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs);

private:
  vtkVIMLOPRegistration(const vtkVIMLOPRegistration&) = delete;
  void operator=(const vtkVIMLOPRegistration&) = delete;

  /// The model for `surface`, rebuilt when the surface or the backend changed.
  const vimlop::RegistrationModel& ModelFor(vtkPolyData* surface);
  /// Sets an option and marks the filter modified when the value changes.
  template <typename T>
  void SetOption(T& field, T value);

  /// The starts of the execution: the given ones, canonical ones, or the initial transform.
  std::vector<vimlop::SimilarityTransform> StartsFor(const vimlop::RegistrationModel& model) const;

  vimlop::RegistrationOptions Options;
  vimlop::MultiStartOptions MultiStart;
  vimlop::CanonicalPoseOptions Canonical;
  vtkSmartPointer<vtkTransformCollection> Starts;
  bool StartFromCanonicalPoses = false;
  double InitialScale = 0.0;
  VisibilityBackend Backend = VisibilityBackend::Embree;
  double DefaultPointSigmaMm = 0.5;
  vtkSmartPointer<vtkLinearTransform> InitialTransform;
  vtkNew<vtkTransform> Transform;

  std::unique_ptr<vimlop::RegistrationModel> Model;
  vtkSmartPointer<vtkVIMLOPDepthVisibility> DepthVisibility;
  vtkMTimeType ModelTime = 0;
  const void* ModelSource = nullptr;
  VisibilityBackend ModelBackend = VisibilityBackend::Embree;

  vimlop::RegistrationData Data;
  vimlop::RegistrationResult Result;
  vimlop::IterationRecord Current; ///< the iteration an IterationEvent reports
  vimlop::MultiStartResult Outcome;
};

#endif
