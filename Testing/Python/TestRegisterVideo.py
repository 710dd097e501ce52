"""The main job from Python: vimlop.register_video() on a simulated sequence.

The sequence is the one the CLI test vimlop.simulate.cranium-upright writes
(30 frames of the bundled CT's airway, the scope held upright, with its true
poses and a tracker recording). The registration starts from canonical
poses along the airway (a multi-start); its camera poses are checked against
the truth and it must not be flagged as a failure. Then: its defaults are
those of `vimlop register` and of both VTK classes, and bad input raises an
error that says what is wrong. Exits non-zero on any failure.

Usage: python3 TestRegisterVideo.py <simulation folder> <CT> <vimlop program>
"""

import json
import os
import subprocess
import sys

import numpy

import vimlop

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


simulation, ct, program = sys.argv[1:4]
result = vimlop.register_video(ct=ct, frames=os.path.join(simulation, "frames"),
                               intrinsics=os.path.join(simulation, "intrinsics.yaml"),
                               tracker=os.path.join(simulation, "tracker.csv"))
with open(os.path.join(simulation, "truth", "poses.json")) as f:
    truth = {p["frame_id"]: numpy.array(p["camera_to_ct"]).reshape(4, 4)
             for p in json.load(f)["poses"]}
errors = [numpy.linalg.norm(pose[:3, 3] - truth[int(frame)][:3, 3])
          for frame, pose in zip(result["frame_ids"], result["camera_to_ct"])]
mean_error = float(numpy.mean(errors))
print("%d frames from %d candidates: camera error %.3f mm (max %.3f), contour error %.2f px"
      % (len(errors), result["candidates"], mean_error, max(errors),
         result["mean_contour_error_px"]))
check(result["camera_to_ct"].shape == (len(result["frame_ids"]), 4, 4),
      "camera_to_ct is an (n, 4, 4) array")
check(len(errors) >= 20, "at least 20 of 30 frames registered (%d)" % len(errors))
check(result["candidates"] > 100, "a multi-start from canonical poses (%d candidates)"
      % result["candidates"])
check(mean_error < 1.0, "mean camera error %.3f mm < 1 mm" % mean_error)
check(not result["flagged_as_failure"], "not flagged as a failure")
check(abs(numpy.linalg.det(result["sfm_to_ct"][:3, :3]) ** (1 / 3) - 1.0) < 10.0,
      "sfm_to_ct is a similarity with a scale")

# One set of defaults: the command line, the pipeline's VTK source and the filter.
printed = subprocess.run([program, "register", "--print-options", "--frames", "f",
                          "--intrinsics", "i", "--out", "o"],
                         check=True, capture_output=True, text=True).stdout
cli = json.loads(printed)
source = json.loads(vimlop.vtkVIMLOPVideoRegistration().GetOptionsAsJSON())
check(cli == source, "vimlop register and vtkVIMLOPVideoRegistration show the same settings")
flt = vimlop.vtkVIMLOPRegistration()
covariance = [0.0, 0.0, 0.0]
flt.GetContourPositionCovariancePx2(covariance)
r = cli["registration"]
check(r["contour_position_covariance_px2"] == [[covariance[0], covariance[1]],
                                               [covariance[1], covariance[2]]],
      "vtkVIMLOPRegistration's contour covariance is the same")


def vtk_name(key):
    """The VTK property of a JSON key, as the option tables name them."""
    return "NumberOfThreads" if key == "threads" else "".join(
        word.capitalize() for word in key.split("_"))


# Every setting of the option table, whatever it holds: the filter (the
# VTK face of Core's defaults) and the pipeline's VTK source must agree.
source_filter = vimlop.vtkVIMLOPVideoRegistration()
compared = 0
for key, value in r.items():
    if key in ("method", "contour_position_covariance_px2", "min_scale", "max_scale"):
        continue
    name = vtk_name(key)
    for face in (flt, source_filter):
        check(getattr(face, "Get" + name)() == value,
              "%s.Get%s() == %s" % (face.GetClassName(), name, value))
    compared += 1
check(compared >= 20, "%d registration settings compared" % compared)
for key in ("failure_threshold_px", "failure_residual_mm", "finalists", "canonical_spacing_mm", "scale_bound_factor"):
    check(getattr(source_filter, "Get" + vtk_name(key))() == cli[key],
          "vtkVIMLOPVideoRegistration.Get%s() == %s" % (vtk_name(key), cli[key]))
check(flt.GetFailureThresholdPx() == cli["failure_threshold_px"],
      "and the filter's failure threshold")
check(flt.GetFailureResidualMm() == cli["failure_residual_mm"],
      "and the filter's failure threshold on the 3-D residual")
source_filter.SetTrimFraction(7.0)
check(source_filter.GetTrimFraction() == source_filter.GetTrimFractionMaxValue() == 0.9,
      "a value outside the table's range is clamped into it")

# Bad input: an error that names the problem.
try:
    vimlop.register_video(ct=ct, frames=os.path.join(simulation, "no-such-folder"),
                          intrinsics=os.path.join(simulation, "intrinsics.yaml"), scale=0.5)
    check(False, "a missing frame folder raises RegistrationError")
except vimlop.RegistrationError as e:
    check("no-such-folder" in str(e), "a missing frame folder raises: %s" % e)
try:
    vimlop.register_video(frames="f", intrinsics="i")
    check(False, "neither ct nor mesh raises ValueError")
except ValueError as e:
    check("ct and mesh" in str(e), "neither ct nor mesh raises: %s" % e)

sys.exit(1 if failures else 0)
