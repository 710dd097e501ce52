// Numerical robustness of the registration (issue 9): degenerate meshes and
// data either register or end with a termination reason that says why, and
// no NaN reaches a result.
#include "TestMeshes.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/SyntheticExperiment.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

using namespace vimlop;

namespace
{

const RegistrationModel& cavityModel()
{
  static const RegistrationModel model(fixtures::makeCavityWithBlobs());
  return model;
}

SyntheticTrial smallTrial(const RegistrationModel& model, std::uint64_t seed)
{
  SyntheticOptions o;
  o.points = 300;
  o.cameras = 4;
  return makeSyntheticTrial(model, o, seed);
}

RegistrationOptions optionsFor(RegistrationMethod method)
{
  RegistrationOptions o;
  o.method = method;
  o.minScale = 0.8;
  o.maxScale = 1.25;
  o.maxIterations = 60;
  return o;
}

/// Every number a caller reads from a result is finite.
void expectFinite(const RegistrationResult& r)
{
  EXPECT_TRUE(r.sfmToCT.matrix().allFinite()) << r.sfmToCT.matrix();
  EXPECT_TRUE(std::isfinite(r.residualErrorMm)) << r.residualErrorMm;
  EXPECT_TRUE(std::isfinite(r.contourErrorPx)) << r.contourErrorPx;
  EXPECT_TRUE(std::isfinite(r.contourErrorInliersPx)) << r.contourErrorInliersPx;
  for (const FrameResult& f : r.frames)
  {
    EXPECT_TRUE(f.cameraToCT.matrix().allFinite()) << "frame " << f.frameId;
    EXPECT_TRUE(std::isfinite(f.contourErrorPx)) << "frame " << f.frameId;
  }
  for (const Eigen::Vector3d& m : r.pointMatches)
  {
    EXPECT_TRUE(m.allFinite());
  }
  for (const IterationRecord& i : r.history)
  {
    EXPECT_TRUE(std::isfinite(i.cost)) << "iteration " << i.iteration;
    EXPECT_TRUE(i.transform.matrix().allFinite()) << "iteration " << i.iteration;
  }
}

/// Runs a registration that may refuse its input; a refusal must be a
/// vimlop::Error with a message, a result must be finite. Returns the result
/// or nothing when refused.
std::optional<RegistrationResult> runOrRefuse(const RegistrationModel& model,
  const RegistrationData& data, const SimilarityTransform& initial, const RegistrationOptions& o,
  std::string* refusal = nullptr)
{
  try
  {
    RegistrationResult r = registerVideo(model, data, initial, o);
    expectFinite(r);
    EXPECT_EQ(r.history.size(), static_cast<size_t>(r.iterations));
    return r;
  }
  catch (const Error& e)
  {
    EXPECT_GT(std::string(e.what()).size(), 10u);
    if (refusal)
    {
      *refusal = e.what();
    }
    return std::nullopt;
  }
}

/// The cavity with the defects of meshes from real segmentations and
/// exporters: zero-area faces (three coincident corners, three collinear corners),
/// duplicated vertices that split the surface along seams, and holes.
TriangleMesh degenerateCavity()
{
  const TriangleMesh clean = fixtures::makeCavityWithBlobs();
  std::vector<Eigen::Vector3d> v = clean.vertices();
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < clean.numberOfFaces(); ++i)
  {
    Eigen::Vector3i face = clean.faces()[static_cast<size_t>(i)];
    if (i % 97 == 5)
    {
      continue; // a hole
    }
    if (i % 7 == 0)
    {
      // This face gets its own copies of its corners (a seam of duplicates).
      for (int c = 0; c < 3; ++c)
      {
        v.push_back(v[static_cast<size_t>(face[c])]);
        face[c] = static_cast<int>(v.size()) - 1;
      }
    }
    f.push_back(face);
    if (i % 11 == 0)
    {
      // Three distinct vertices at one place (a face collapsed by decimation).
      v.push_back(v[static_cast<size_t>(face[0])]);
      v.push_back(v[static_cast<size_t>(face[0])]);
      f.emplace_back(face[0], static_cast<int>(v.size()) - 2, static_cast<int>(v.size()) - 1);
      const Eigen::Vector3d middle =
        0.5 * (v[static_cast<size_t>(face[1])] + v[static_cast<size_t>(face[2])]);
      v.push_back(middle);
      f.emplace_back(face[1], static_cast<int>(v.size()) - 1, face[2]); // collinear corners
    }
  }
  return TriangleMesh(std::move(v), std::move(f));
}

} // namespace

TEST(NumericalRobustness, FaceRepeatingAVertexIsRefused)
{
  // A face that names one vertex twice is not a triangle (mesh readers drop
  // such faces, see toTriangleMesh()); the mesh itself refuses it by name.
  try
  {
    TriangleMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 }, { 0, 0, 1 } });
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "mesh face 1 repeats a vertex (0 0 1)");
  }
}

TEST(NumericalRobustness, DegenerateMeshRegisters)
{
  const TriangleMesh mesh = degenerateCavity();
  ASSERT_GT(mesh.numberOfBoundaryEdges(), 0);
  int zeroArea = 0;
  for (double a : mesh.faceAreas())
  {
    zeroArea += a == 0.0;
  }
  ASSERT_GT(zeroArea, 100);
  for (const Eigen::Vector3d& n : mesh.faceNormals())
  {
    ASSERT_TRUE(n.allFinite());
  }
  for (const Eigen::Vector3d& n : mesh.vertexNormals())
  {
    ASSERT_TRUE(n.allFinite());
  }
  const RegistrationModel model(mesh);
  // The data come from the clean cavity: the defects must not matter.
  const SyntheticTrial trial = smallTrial(cavityModel(), 11);
  for (RegistrationMethod method : { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP })
  {
    const auto r = runOrRefuse(model, trial.data, trial.initialSfmToCT, optionsFor(method));
    ASSERT_TRUE(r) << toString(method);
    EXPECT_LT(targetRegistrationError(r->sfmToCT, trial.truthSfmToCT, trial.targetsCT), 1.0)
      << toString(method) << ": " << toString(r->termination);
  }
}

TEST(NumericalRobustness, CollinearAndCoincidentPoints)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = smallTrial(model, 12);
  // All points on one line; all points at one place: rotation about the
  // line (or every rotation) is unobservable from the points.
  RegistrationData line = trial.data;
  RegistrationData point = trial.data;
  const Eigen::Vector3d a = trial.data.points.front();
  const Eigen::Vector3d b = trial.data.points.back();
  for (size_t i = 0; i < line.points.size(); ++i)
  {
    const double t = static_cast<double>(i) / static_cast<double>(line.points.size() - 1);
    line.points[i] = a + t * (b - a);
    point.points[i] = a;
  }
  for (const RegistrationData* data : { &line, &point })
  {
    for (RegistrationMethod method :
      { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP, RegistrationMethod::TrimmedICP })
    {
      SCOPED_TRACE(std::string(toString(method)) + (data == &line ? " line" : " point"));
      runOrRefuse(model, *data, trial.initialSfmToCT, optionsFor(method));
    }
  }
}

TEST(NumericalRobustness, CameraOnTheSurface)
{
  // A box cavity and a camera whose centre lies exactly on its ceiling.
  const RegistrationModel model(fixtures::makeBox({ -10, -10, -10 }, { 10, 10, 10 }));
  RegistrationData data;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-9.0, 9.0);
  for (int i = 0; i < 200; ++i)
  {
    data.points.emplace_back(u(rng), u(rng), -10.0);
    data.pointCovariances.push_back(0.04 * Eigen::Matrix3d::Identity());
  }
  VideoFrame frame;
  frame.intrinsics = PinholeCamera::simulatedEndoscope();
  frame.cameraToSfm = CameraPose::lookAt({ 0, 0, 10 }, { 0, 0, 0 }, { 0, 1, 0 });
  data.frames.push_back(frame);
  RegistrationOptions options = optionsFor(RegistrationMethod::IMLP);
  options.minScale = options.maxScale = 1.0;
  std::string refusal;
  const auto r = runOrRefuse(model, data, SimilarityTransform(), options, &refusal);
  if (r)
  {
    // Kept inside (or on) the cavity by the anatomical constraint.
    EXPECT_LE(r->frames[0].cameraToCT.centre.z(), 10.0 + 1e-9);
  }
  else
  {
    EXPECT_EQ(refusal.rfind("registration: the camera of frame ", 0), 0u) << refusal;
  }
}

TEST(NumericalRobustness, NearSingularCovariances)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = smallTrial(model, 13);
  RegistrationData data = trial.data;
  for (size_t i = 0; i < data.pointCovariances.size(); ++i)
  {
    // Flat along a random direction: eigenvalues 0.25, 0.25 and 1e-12 mm^2
    // (or 1e-300 every tenth point, which is no longer numerically positive).
    Eigen::Vector3d n = Eigen::Vector3d::Random().normalized();
    const double tiny = i % 10 == 0 ? 1e-300 : 1e-12;
    data.pointCovariances[i] =
      0.25 * (Eigen::Matrix3d::Identity() - n * n.transpose()) + tiny * n * n.transpose();
  }
  for (RegistrationMethod method : { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP })
  {
    SCOPED_TRACE(toString(method));
    runOrRefuse(model, data, trial.initialSfmToCT, optionsFor(method));
  }
}

TEST(NumericalRobustness, AllOutlierFrames)
{
  const RegistrationModel& model = cavityModel();
  const SyntheticTrial trial = smallTrial(model, 14);
  // Contours that match nothing: every contour point of every frame in a
  // corner of the image with a normal pointing away from any model contour.
  RegistrationData contours = trial.data;
  for (VideoFrame& f : contours.frames)
  {
    for (ContourPoint& c : f.contour)
    {
      c.pixel = Eigen::Vector2d(1.0, 1.0);
      c.normal = Eigen::Vector2d(-1.0, 0.0);
    }
  }
  SCOPED_TRACE("contours");
  const auto r =
    runOrRefuse(model, contours, trial.initialSfmToCT, optionsFor(RegistrationMethod::VIMLOP));
  if (r)
  {
    EXPECT_NE(r->termination, TerminationReason::NumericalFailure);
  }
  // Points that lie nowhere near the surface: 200 mm away, in every direction.
  RegistrationData points = trial.data;
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  for (Eigen::Vector3d& p : points.points)
  {
    p = 200.0 * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  }
  for (RegistrationMethod method :
    { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP, RegistrationMethod::TrimmedICP })
  {
    SCOPED_TRACE(std::string("points ") + toString(method));
    runOrRefuse(model, points, trial.initialSfmToCT, optionsFor(method));
  }
}
