// Registers a synthetic P1 trial on a model built in memory, with the
// installed headers and libraries only, and prints the transform and the
// camera pose table the VTK side of VIMLOP produces.
#include <CameraPoseTable.h>
#include <EmbreeRegistrationModel.h>
#include <Registration.h>
#include <RegistrationMetrics.h>
#include <SyntheticExperiment.h>

#include <vtkTable.h>

#include <cmath>
#include <iostream>

namespace
{

/// A closed cavity with a solid blob inside (normals into the air).
vimlop::TriangleMesh makeModel()
{
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  auto addSphere = [&](const Eigen::Vector3d& centre, double radius, bool cavity) {
    const int rings = 40;
    const int segments = 80;
    const int first = static_cast<int>(vertices.size());
    for (int i = 0; i <= rings; ++i)
    {
      const double theta = M_PI * i / rings;
      for (int j = 0; j < segments; ++j)
      {
        const double phi = 2.0 * M_PI * j / segments;
        const double bump = cavity ? 1.0 + 0.15 * std::sin(3 * theta) * std::cos(2 * phi) : 1.0;
        vertices.push_back(centre + radius * bump *
            Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      }
    }
    for (int i = 0; i < rings; ++i)
    {
      for (int j = 0; j < segments; ++j)
      {
        const int a = first + i * segments + j;
        const int b = first + i * segments + (j + 1) % segments;
        const int c = a + segments;
        const int d = b + segments;
        // Outward winding (a, c, d), flipped for the cavity so normals face the air.
        if (i > 0)
          faces.push_back(cavity ? Eigen::Vector3i(a, b, c) : Eigen::Vector3i(a, c, b));
        if (i < rings - 1)
          faces.push_back(cavity ? Eigen::Vector3i(b, d, c) : Eigen::Vector3i(b, c, d));
      }
    }
  };
  addSphere(Eigen::Vector3d::Zero(), 20.0, true);
  addSphere(Eigen::Vector3d(8.0, 0.0, 3.0), 4.0, false);
  return vimlop::TriangleMesh(vertices, faces);
}

} // namespace

int main()
{
  const vimlop::TriangleMesh mesh = makeModel();
  const vimlop::RegistrationModel model = vimlop::makeEmbreeRegistrationModel(mesh);
  vimlop::SyntheticOptions synthetic;
  synthetic.points = 400;
  const vimlop::SyntheticTrial trial = vimlop::makeSyntheticTrial(model, synthetic, 3);
  vimlop::RegistrationOptions options;
  options.minScale = 0.8;
  options.maxScale = 1.25;
  const vimlop::RegistrationResult result =
    vimlop::registerVideo(model, trial.data, trial.initialSfmToCT, options);
  std::vector<vimlop::FramePose> poses;
  for (const vimlop::FrameResult& frame : result.frames)
  {
    poses.push_back({ frame.frameId, frame.cameraToCT });
  }
  const vtkSmartPointer<vtkTable> table = vimlop::makeCameraPoseTable(poses);
  const double tre = vimlop::targetRegistrationError(result.sfmToCT, trial.truthSfmToCT, trial.targetsCT);
  std::cout << "SfM to CT transform:\n" << result.sfmToCT.matrix() << "\n";
  std::cout << "camera pose table: " << table->GetNumberOfRows() << " rows\n";
  std::cout << "TRE " << tre << " mm\n";
  return tre < 1.0 && table->GetNumberOfRows() == 6 ? 0 : 1;
}
