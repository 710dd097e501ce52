"""Registers a P1 trial in a VTK Python pipeline through `import vimlop`.

The trial is a result folder written by `vimlop evaluate synthetic
--save-trial`: its input files feed vtkVIMLOPRegistration through VTK's XML
readers, the start is the trial's initial transform, and the transform that
GetTransform() offers is checked against the ground truth in result.json
(target registration error over targets.vtp) and against the C++ program's
own run of the same data. Exits non-zero on any failure.

Usage: python3 TestP1Pipeline.py <result folder>
"""

import json
import math
import os
import sys

from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLTableReader

import vimlop

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def transform_of(rows):
    """A vtkTransform from a 4 x 4 matrix given as a list of rows."""
    transform = vtkTransform()
    transform.SetMatrix([value for row in rows for value in row])
    return transform


def reader(cls, folder, name):
    r = cls()
    r.SetFileName(os.path.join(folder, name))
    return r


folder = sys.argv[1]
with open(os.path.join(folder, "result.json")) as f:
    result = json.load(f)

model = reader(vtkXMLPolyDataReader, folder, "model.vtp")
points = reader(vtkXMLPolyDataReader, folder, "sfm-points.vtp")
frames = reader(vtkXMLTableReader, folder, "frame-table.vtt")
contours = reader(vtkXMLPolyDataReader, folder, "video-contours.vtp")

registration = vimlop.vtkVIMLOPRegistration()
registration.SetModelConnection(model.GetOutputPort())
registration.SetPointsConnection(points.GetOutputPort())
registration.SetFramesConnection(frames.GetOutputPort())
registration.SetContoursConnection(contours.GetOutputPort())
registration.SetInitialTransform(transform_of(result["initial_transform"]["matrix"]))
# The parameters the C++ run used (P1's: the paper's synthetic noise and
# stall rule), which differ from the filter's defaults (the video ones).
parameters = result["parameters"]
if isinstance(parameters.get("min_scale"), (int, float)):
    registration.SetMinScale(parameters["min_scale"])
if isinstance(parameters.get("max_scale"), (int, float)):
    registration.SetMaxScale(parameters["max_scale"])
covariance = parameters["contour_position_covariance_px2"]
registration.SetContourPositionCovariancePx2(covariance[0][0], covariance[0][1], covariance[1][1])
registration.SetContourKappa(parameters["contour_kappa"])
registration.SetStallRelativeDecrease(parameters["stall_relative_decrease"])
registration.SetStallIterations(parameters["stall_iterations"])
registration.SetMaxIterations(parameters["max_iterations"])

# One IterationEvent per iteration; its estimate is read with GetCurrent...()
# (GetTransform() changes when the execution ends).
scales = []
iterations = []


def on_iteration(caller, event):
    scales.append(caller.GetCurrentScale())
    iterations.append(caller.GetCurrentIteration())


registration.AddObserver(vimlop.vtkVIMLOPRegistration.IterationEvent, on_iteration)

# Downstream SfM-frame data follows the live transform.
points_in_ct = vtkTransformPolyDataFilter()
points_in_ct.SetInputConnection(points.GetOutputPort())
points_in_ct.SetTransform(registration.GetTransform())

registration.Update()
points_in_ct.Update()

matrix = registration.GetTransform().GetMatrix()
print("vtkVIMLOPRegistration.GetTransform() (SfM to CT, mm):")
for i in range(4):
    print("  " + " ".join("%10.5f" % matrix.GetElement(i, j) for j in range(4)))
print("%d iterations, %d iteration events, scale %.4f"
      % (registration.GetNumberOfIterations(), len(scales), matrix.Determinant() ** (1.0 / 3.0)))

# TRE: each target taken into the SfM frame by the truth, then into the CT by the estimate.
truth_inverse = transform_of(result["ground_truth"]["transform"]["matrix"]).GetInverse()
targets = reader(vtkXMLPolyDataReader, folder, "targets.vtp")
targets.Update()
target_points = targets.GetOutput().GetPoints()
total = 0.0
for k in range(target_points.GetNumberOfPoints()):
    y = target_points.GetPoint(k)
    mapped = registration.GetTransform().TransformPoint(truth_inverse.TransformPoint(y))
    total += math.dist(mapped, y)
tre = total / target_points.GetNumberOfPoints()
cpp_tre = result["ground_truth"]["tre_mm"]
print("TRE %.4f mm over %d targets (the C++ run of the same data: %.4f mm)"
      % (tre, target_points.GetNumberOfPoints(), cpp_tre))

check(tre < 0.5, "the registration is accurate: TRE %.4f mm < 0.5 mm" % tre)
check(abs(tre - cpp_tre) < 0.01, "Python reproduces the C++ run within 0.01 mm of TRE")
check(len(scales) > 0 and len(scales) <= registration.GetNumberOfIterations(),
      "one IterationEvent per updating iteration (%d events)" % len(scales))
check(iterations == sorted(set(iterations)), "the events report successive iterations")
check(len(set(round(s, 6) for s in scales)) > 1,
      "the observer sees the scale change: %.4f .. %.4f" % (min(scales), max(scales)))
poses = registration.GetCameraPoses()
check(poses.GetNumberOfRows() == len(result["frames"]),
      "camera pose table: %d rows for %d frames" % (poses.GetNumberOfRows(), len(result["frames"])))

# The transform filter downstream and the filter's own registered points agree.
moved = points_in_ct.GetOutput().GetPoints()
registered = registration.GetRegisteredPoints().GetPoints()
worst = max(math.dist(moved.GetPoint(i), registered.GetPoint(i)) for i in range(moved.GetNumberOfPoints()))
check(moved.GetNumberOfPoints() == registered.GetNumberOfPoints() and worst < 1e-6,
      "points moved by GetTransform() downstream match the registered points (worst %.2g mm)" % worst)

sys.exit(1 if failures else 0)
