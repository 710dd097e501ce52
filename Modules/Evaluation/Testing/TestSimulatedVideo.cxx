#include "TestMeshes.h"
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

TEST(SimulatedVideo, MeasuresItsPathAndItsLeastDistanceToTheWall)
{
  SimulatedVideo video;
  EXPECT_EQ(video.pathLengthMm(), 0.0);
  for (const Eigen::Vector3d& centre :
    { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(3, 4, 0) })
  {
    CameraPose camera;
    camera.centre = centre;
    video.camerasCT.push_back(camera);
  }
  EXPECT_DOUBLE_EQ(video.pathLengthMm(), 7.0);

  // Inside a sphere of radius 20 mm: the camera 5 mm from the centre is the closest to the wall.
  const RegistrationModel model = makeEmbreeRegistrationModel(fixtures::makeSphere(20.0, 4));
  EXPECT_NEAR(video.leastWallDistanceMm(model), 15.0, 0.2);
  EXPECT_TRUE(std::isinf(SimulatedVideo().leastWallDistanceMm(model)));
}
