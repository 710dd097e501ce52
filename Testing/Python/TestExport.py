"""The files of `vimlop export`, read back in Python without VIMLOP's code.

Reads the registration's own camera poses and SfM-to-CT transform from its
result.json, then each exported form of them, with the readers a Python
user has: the ITK text transform files parsed as ITK documents them, the
ITK HDF5 ones through h5py (ITK's TransformGroup layout), the Slicer linear
transform sequence (a MetaImage header of Seq_Frame fields), and the meshes
through VTK. Every pose must come back to 1e-9; the scene must name files
that are there. Exits non-zero on any failure.

Usage: python3 TestExport.py <result folder> <export, .tfm> <export, .h5>
"""

import json
import os
import re
import sys

import h5py
import numpy
from vtkmodules.vtkIOLegacy import vtkPolyDataReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def affine(parameters, fixed):
    """The 4 x 4 point map of an ITK AffineTransform: A (x - c) + t + c."""
    matrix = numpy.identity(4)
    matrix[:3, :3] = numpy.array(parameters[:9]).reshape(3, 3)
    centre = numpy.array(fixed[:3]) if len(fixed) else numpy.zeros(3)
    matrix[:3, 3] = numpy.array(parameters[9:12]) + centre - matrix[:3, :3] @ centre
    return matrix


def read_tfm(path):
    fields = {}
    with open(path) as f:
        for line in f:
            if ":" in line and not line.startswith("#"):
                key, value = line.split(":", 1)
                fields[key.strip()] = value.split()
    if fields["Transform"] != ["AffineTransform_double_3_3"]:
        check(False, path + " is an ITK affine transform")
    return affine([float(v) for v in fields["Parameters"]],
                  [float(v) for v in fields["FixedParameters"]])


def read_h5(path):
    with h5py.File(path, "r") as f:
        group = f["TransformGroup"]["0"]
        kind = group["TransformType"][0]
        kind = kind.decode() if isinstance(kind, bytes) else str(kind)
        if kind != "AffineTransform_double_3_3":
            check(False, path + " is an ITK affine transform")
        return affine(list(group["TransformParameters"][:]), list(group["TransformFixedParameters"][:]))


def read_sequence(path, name):
    matrices, times = {}, {}
    pattern = re.compile(r"Seq_Frame(\d+)_(\w+) = ?(.*)")
    with open(path) as f:
        for line in f:
            found = pattern.match(line.strip())
            if not found:
                continue
            frame, field, value = int(found.group(1)), found.group(2), found.group(3)
            if field == name + "Transform":
                matrices[frame] = numpy.array([float(v) for v in value.split()]).reshape(4, 4)
            elif field == "Timestamp":
                times[frame] = float(value)
    return [(times[k], matrices[k]) for k in sorted(matrices)]


def points_of(reader, path):
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput().GetNumberOfPoints()


result_folder, export_tfm, export_h5 = sys.argv[1:4]
with open(os.path.join(result_folder, "result.json")) as f:
    result = json.load(f)
poses = {frame["id"]: numpy.array(frame["camera_to_ct"]) for frame in result["frames"]}
sfm_to_ct = numpy.array(result["transform"]["matrix"])
check(len(poses) > 0, "the result has %d camera poses" % len(poses))

for folder, reader in ((export_tfm, read_tfm), (export_h5, read_h5)):
    extension = ".tfm" if reader is read_tfm else ".h5"
    worst = 0.0
    for frame_id, pose in poses.items():
        # ITK's resampling form: the file maps CT points to camera points.
        path = os.path.join(folder, "Transforms", "CameraToCT-%04d%s" % (frame_id, extension))
        worst = max(worst, numpy.abs(numpy.linalg.inv(reader(path)) - pose).max())
    check(worst < 1e-9, "every %s camera pose reads back to the result's (worst %.3g)" % (extension, worst))
    ct_to_sfm = reader(os.path.join(folder, "Transforms", "SfMToCT" + extension))
    error = numpy.abs(numpy.linalg.inv(ct_to_sfm) - sfm_to_ct).max()
    check(error < 1e-9, "the %s SfM-to-CT similarity reads back to the result's (%.3g)" % (extension, error))

# Slicer's sequence: camera to RAS (LPS flipped in x and y), at the frame times.
lps_to_ras = numpy.diag([-1.0, -1.0, 1.0, 1.0])
sequence = read_sequence(os.path.join(export_tfm, "CameraToCT.seq.mha"), "CameraToCT")
check(len(sequence) == len(poses), "the sequence has one item per pose (%d)" % len(sequence))
worst = max(numpy.abs(matrix - lps_to_ras @ pose).max()
            for (time, matrix), pose in zip(sequence, poses.values()))
check(worst < 1e-9, "the sequence holds every camera-to-RAS pose (worst %.3g)" % worst)
frame_times = [frame["time_s"] for frame in result["frames"] if "time_s" in frame]
if frame_times:
    check([t for t, _ in sequence] == frame_times, "the sequence's times are the frames' times")

# The meshes, through VTK.
airway = points_of(vtkPolyDataReader(), os.path.join(export_tfm, "Airway.vtk"))
model = points_of(vtkXMLPolyDataReader(), os.path.join(result_folder, "model.vtp"))
check(airway == model and airway > 0, "Airway.vtk has the model's %d points (%d)" % (model, airway))
with open(os.path.join(export_tfm, "Airway.vtk"), "rb") as f:
    check(b"SPACE=LPS" in f.readline() + f.readline(), "Airway.vtk says its frame is LPS")

with open(os.path.join(export_tfm, "Scene.mrml")) as f:
    scene = f.read()
names = re.findall(r'fileName="([^"]+)"', scene)
missing = [n for n in names if not os.path.exists(os.path.join(export_tfm, n))]
check(len(names) >= 5 and not missing, "the scene names %d files, all there %s" % (len(names), missing))

sys.exit(1 if failures else 0)
