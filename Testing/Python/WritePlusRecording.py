"""Writes a simulated sequence as a PLUS tracked recording (.igs.mha, .igs.nrrd)
or a 3D Slicer volume sequence (.seq.nrrd).

What a lab's PLUS or 3D Slicer session records from a tracked endoscope:
the frames (RGB, in one MetaImage whose third axis is time), a timestamp per
frame on the tracker's clock at the given frame rate, and the transform
ProbeToTracker of every frame: the scope's true pose (the simulation's
truth), seen from an electromagnetic field generator placed somewhere
relative to the CT, with the tracker's noise on its position and its
rotation. Every frame is written with status OK. Beside it, <name>-TrackerToRAS.tfm:
the tracker registered to the patient as 3D Slicer saves that transform
(an ITK file of the inverse map, both spaces taken as LPS), with the error
of a navigation system's patient registration.

The form follows the name: `.igs.mha` is PLUS's MetaImage (raw), `.igs.nrrd`
PLUS's NRRD (gzip), `.seq.nrrd` the volume sequence Slicer saves from a
sequence browser (frames and their times as the sequence index, no
transform), its ProbeToTracker written beside it as the linear transform
sequence Slicer saves (`ProbeToTracker.seq.mha`). The frames, times and
transforms are the same in every form.

Usage: python3 WritePlusRecording.py <simulation folder> <out.igs.mha|.igs.nrrd|.seq.nrrd> [fps]
"""

import gzip
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
noise_deg = 0.3   # its orientation noise (a few tenths of a degree)
# The patient registration's error (fiducials or surface: 1-2 mm and a few
# degrees in sinus navigation): 3 degrees about an oblique axis, 1.5 mm.
registration_error_deg = 3.0
registration_error_mm = [1.0, -0.8, 0.8]

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
rotation_rng = numpy.random.default_rng(8)  # apart, so that the positions stay those of seed 7


def rotation(axis, angle_deg):
    """The rotation matrix of angle_deg about axis (Rodrigues)."""
    axis = numpy.asarray(axis, dtype=float) / numpy.linalg.norm(axis)
    k = numpy.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = math.radians(angle_deg)
    return numpy.identity(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k

pixels = []
for name in names:
    reader = vtkPNGReader()
    reader.SetFileName(os.path.join(frames_folder, name))
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :, :3]
    pixels.append(rgb[::-1])  # VTK's first row is the bottom one; PLUS's (MF) the top one

frame_fields = []  # per frame: (name, value) pairs, PLUS's Seq_Frame<n>_ fields
times_s = []
for index, name in enumerate(names):
    frame_id = int("".join(c for c in name if c.isdigit()))
    probe_to_tracker = tracker_from_ct @ truth[frame_id]
    probe_to_tracker[:3, 3] += rng.normal(0.0, noise_mm, 3)
    probe_to_tracker[:3, :3] = probe_to_tracker[:3, :3] @ rotation(
        rotation_rng.normal(size=3), rotation_rng.normal(0.0, noise_deg))
    times_s.append("%.6f" % (start_s + index / fps))
    frame_fields.append([("ProbeToTrackerTransform", " ".join("%.17g" % v for v in probe_to_tracker.ravel())),
                         ("ProbeToTrackerTransformStatus", "OK"), ("Timestamp", times_s[-1]),
                         ("ImageStatus", "OK")])
data = b"".join(numpy.ascontiguousarray(rgb, dtype=numpy.uint8).tobytes() for rgb in pixels)


def frame_lines(separator, fields=frame_fields):
    return ["Seq_Frame%04d_%s%s%s" % (index, key, separator, value)
            for index, pairs in enumerate(fields) for key, value in pairs]


if out.endswith(".mha"):
    header = ["ObjectType = Image", "NDims = 3", "AnatomicalOrientation = RAI", "BinaryData = True",
              "BinaryDataByteOrderMSB = False", "CompressedData = False",
              "DimSize = %d %d %d" % (width, height, len(names)), "ElementNumberOfChannels = 3",
              "ElementSpacing = 1 1 1", "ElementType = MET_UCHAR", "Kinds = domain domain list",
              "Offset = 0 0 0", "TransformMatrix = 1 0 0 0 1 0 0 0 1",
              "UltrasoundImageOrientation = MF", "UltrasoundImageType = RGB_COLOR"]
    header += frame_lines(" = ") + ["ElementDataFile = LOCAL"]
    body = data
elif out.endswith(".igs.nrrd"):
    header = ["NRRD0004", "# Complete NRRD file format specification at:",
              "# http://teem.sourceforge.net/nrrd/format.html", "type: unsigned char", "dimension: 5",
              "space: left-posterior-superior", "sizes: 3 %d %d 1 %d" % (width, height, len(names)),
              "kinds: vector domain domain domain list", "encoding: gzip",
              "UltrasoundImageOrientation:=MF", "UltrasoundImageType:=RGB_COLOR"]
    header += frame_lines(":=") + [""]
    body = gzip.compress(data)
elif out.endswith(".seq.nrrd"):
    header = ["NRRD0004", "type: unsigned char", "dimension: 5", "space: left-posterior-superior",
              "sizes: 3 %d %d 1 %d" % (width, height, len(names)),
              "kinds: RGB-color domain domain domain list", 'units: "" "" "" "" "s"',
              "encoding: gzip", "axis 3 index type:=numeric",
              "axis 3 index values:=" + " ".join(times_s), "DataNodeClassName:=vtkMRMLVectorVolumeNode", ""]
    body = gzip.compress(data)
    transforms = ["ObjectType = Image", "NDims = 3", "AnatomicalOrientation = RAI", "BinaryData = True",
                  "CompressedData = False", "DimSize = 0 0 %d" % len(names), "ElementSpacing = 1 1 1",
                  "Offset = 0 0 0", "TransformMatrix = 1 0 0 0 1 0 0 0 1", "ElementType = MET_UCHAR",
                  "Kinds = domain domain list"]
    transforms += frame_lines(" = ", [pairs[:3] for pairs in frame_fields]) + ["ElementDataFile = LOCAL"]
    with open(os.path.join(os.path.dirname(out), "ProbeToTracker.seq.mha"), "w") as f:
        f.write("\n".join(transforms) + "\n")
else:
    sys.exit("the recording's name must end with .igs.mha, .igs.nrrd or .seq.nrrd: " + out)
with open(out, "wb") as f:
    f.write(("\n".join(header) + "\n").encode())
    f.write(body)

# TrackerToRAS as Slicer saves it: the file holds F (TrackerToRAS)^-1 F with
# F = diag(-1, -1, 1), and TrackerToRAS = F TrackerToCT (LPS), so the file is
# F TrackerToCT^-1; the registration's error E moves the CT side.
error = numpy.identity(4)
error[:3, :3] = rotation([1.0, 2.0, 0.5], registration_error_deg)
error[:3, 3] = registration_error_mm
tracker_to_ct = error @ numpy.linalg.inv(tracker_from_ct)
in_file = numpy.diag([-1.0, -1.0, 1.0, 1.0]) @ numpy.linalg.inv(tracker_to_ct)
# Named after the recording (plus-30.igs.mha: plus-30-TrackerToRAS.tfm), written
# whole then renamed: the three forms of one recording write the same file.
transform_file = out.split(".")[0] + "-TrackerToRAS.tfm"
with open(transform_file + ".%d" % os.getpid(), "w") as f:
    f.write("#Insight Transform File V1.0\n#Transform 0\nTransform: AffineTransform_double_3_3\n")
    f.write("Parameters: " + " ".join("%.17g" % v for v in list(in_file[:3, :3].ravel()) + list(in_file[:3, 3])) + "\n")
    f.write("FixedParameters: 0 0 0\n")
os.replace(transform_file + ".%d" % os.getpid(), transform_file)
print("wrote %s: %d frames of %dx%d px at %g fps, ProbeToTracker with %.2f mm and %.1f deg noise; "
      "TrackerToRAS.tfm %.0f deg and %.1f mm off" % (out, len(names), width, height, fps, noise_mm, noise_deg,
                                                   registration_error_deg, numpy.linalg.norm(registration_error_mm)))
