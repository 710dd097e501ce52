"""Writes a simulated sequence as a PLUS tracked recording (.igs.mha).

What a lab's PLUS or 3D Slicer session records from a tracked endoscope:
the frames (RGB, in one MetaImage whose third axis is time), a timestamp per
frame on the tracker's clock at the given frame rate, and the transform
ProbeToTracker of every frame: the scope's true pose (the simulation's
truth), seen from an electromagnetic field generator placed somewhere
relative to the CT, with the tracker's noise on its position. Every frame
is written with status OK.

Usage: python3 WritePlusRecording.py <simulation folder> <out.igs.mha> [fps]
"""

import json
import math
import os
import sys

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

simulation, out = sys.argv[1:3]
fps = float(sys.argv[3]) if len(sys.argv) > 3 else 25.0
start_s = 1000.0  # PLUS stamps frames on the tracker's clock, which did not start with the video
noise_mm = 0.25   # an electromagnetic tracker's position noise (about 0.2-0.5 mm in a clinic)

frames_folder = os.path.join(simulation, "frames")
names = sorted(n for n in os.listdir(frames_folder) if n.endswith(".png"))
with open(os.path.join(simulation, "truth", "poses.json")) as f:
    truth = {p["frame_id"]: numpy.array(p["camera_to_ct"]).reshape(4, 4) for p in json.load(f)["poses"]}

# The field generator: 30 degrees about the CT's z axis, 150 mm away.
angle = math.radians(30.0)
tracker_from_ct = numpy.identity(4)
tracker_from_ct[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
tracker_from_ct[:3, 3] = [40.0, -120.0, 90.0]
rng = numpy.random.default_rng(7)

pixels = []
for name in names:
    reader = vtkPNGReader()
    reader.SetFileName(os.path.join(frames_folder, name))
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :, :3]
    pixels.append(rgb[::-1])  # VTK's first row is the bottom one; PLUS's (MF) the top one

with open(out, "wb") as f:
    header = ["ObjectType = Image", "NDims = 3", "AnatomicalOrientation = RAI", "BinaryData = True",
              "BinaryDataByteOrderMSB = False", "CompressedData = False",
              "DimSize = %d %d %d" % (width, height, len(names)), "ElementNumberOfChannels = 3",
              "ElementSpacing = 1 1 1", "ElementType = MET_UCHAR", "Kinds = domain domain list",
              "Offset = 0 0 0", "TransformMatrix = 1 0 0 0 1 0 0 0 1",
              "UltrasoundImageOrientation = MF", "UltrasoundImageType = RGB_COLOR"]
    for index, name in enumerate(names):
        frame_id = int("".join(c for c in name if c.isdigit()))
        probe_to_tracker = tracker_from_ct @ truth[frame_id]
        probe_to_tracker[:3, 3] += rng.normal(0.0, noise_mm, 3)
        prefix = "Seq_Frame%04d_" % index
        header += [prefix + "ProbeToTrackerTransform = " +
                   " ".join("%.17g" % v for v in probe_to_tracker.ravel()),
                   prefix + "ProbeToTrackerTransformStatus = OK",
                   prefix + "Timestamp = %.6f" % (start_s + index / fps),
                   prefix + "ImageStatus = OK"]
    header.append("ElementDataFile = LOCAL")
    f.write(("\n".join(header) + "\n").encode())
    for rgb in pixels:
        f.write(numpy.ascontiguousarray(rgb, dtype=numpy.uint8).tobytes())
print("wrote %s: %d frames of %dx%d px at %g fps, ProbeToTracker with %.2f mm noise"
      % (out, len(names), width, height, fps, noise_mm))
