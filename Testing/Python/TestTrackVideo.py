"""Tracking from Python: vimlop.track_video() after a registration.

The inputs are those of the CLI tests vimlop.track.*: a 24-frame simulated
sequence of the bundled CT (ideal world), its first 12 frames registered
(track-registered), and `vimlop track`'s own output on the other 12
(tracked), and with the simulation's tracker (tracked-tip). Checks: the 12
frames are tracked near the truth with the same poses as the command line,
with and without the tracker; each pose reaches on_frame as it is computed,
and asking to stop there ends the run after that frame with its outputs
written; the settings are those of `vimlop track`; bad input raises an error
that says what is wrong. Exits non-zero on any failure.

Usage: python3 TestTrackVideo.py <registered result> <simulation folder>
       <vimlop track's output folder> <vimlop program>
"""

import json
import os
import re
import subprocess
import sys

import numpy

import vimlop

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def poses_of(path):
    with open(path) as f:
        return {p["frame_id"]: numpy.array(p["camera_to_ct"]).reshape(4, 4)
                for p in json.load(f)["poses"]}


registered, simulation, cli_output, program = sys.argv[1:5]
frames = os.path.join(simulation, "frames")
intrinsics = os.path.join(simulation, "intrinsics.yaml")
truth = poses_of(os.path.join(simulation, "truth", "poses.json"))

seen = []
tracked = vimlop.track_video(result=registered, frames=frames, intrinsics=intrinsics,
                             on_frame=lambda i, state, pose: seen.append((i, state, pose)))
ids = [int(i) for i in tracked["frame_ids"]]
errors = [numpy.linalg.norm(pose[:3, 3] - truth[i][:3, 3])
          for i, pose in zip(ids, tracked["camera_to_ct"])]
print("%d frames: %d tracking, %d degraded, %d lost; camera error %.3f mm mean (max %.3f)"
      % (len(ids), tracked["tracking"], tracked["degraded"], tracked["lost"],
         numpy.mean(errors), max(errors)))
check(ids == list(range(12, 24)), "the 12 frames after the registered ones (%s)" % ids)
check(tracked["camera_to_ct"].shape == (12, 4, 4), "camera_to_ct is a (12, 4, 4) array")
check(list(tracked["states"]) == ["tracking"] * 12 and tracked["tracking"] == 12,
      "every frame tracking (%s)" % list(tracked["states"]))
check(numpy.mean(errors) < 0.3, "mean camera error %.3f mm < 0.3 mm" % numpy.mean(errors))
check(all(latency > 0.0 for latency in tracked["latency_ms"]), "every frame has a latency")
contours = tracked["contour_error_px"]
check(contours.shape == (12,) and bool(numpy.all(contours < 2.0)),
      "every frame's contours lie within 2 px of the model's at its pose (%s)"
      % numpy.round(contours, 2).tolist())
cli = poses_of(os.path.join(cli_output, "tracked-poses.json"))
difference = max(numpy.abs(pose - cli[i]).max() for i, pose in zip(ids, tracked["camera_to_ct"]))
check(sorted(cli) == ids and difference < 1e-6,
      "the same poses as vimlop track (largest difference %.2g)" % difference)
check([i for i, _, _ in seen] == ids, "on_frame saw every frame as it was tracked, in order")
check(all(numpy.allclose(pose, tracked["camera_to_ct"][k]) for k, (_, _, pose) in enumerate(seen)),
      "on_frame was given each frame's pose")

# Stopping from on_frame (AbortExecute underneath): the run ends after that
# frame, and what was tracked is output and written.
out = "tracked-python-stopped"
stopped = vimlop.track_video(result=registered, frames=frames, intrinsics=intrinsics, out=out,
                             video=False, on_frame=lambda i, state, pose: i == 15)
check(list(stopped["frame_ids"]) == [12, 13, 14, 15],
      "stopping at frame 15 ends the run there (%s)" % list(stopped["frame_ids"]))
with open(os.path.join(out, "tracking.json")) as f:
    report = json.load(f)
check(len(report["per_frame"]) == 4 and report.get("stopped_by", "").startswith("interrupted"),
      "tracking.json holds the 4 frames and says the run was stopped")
check(not os.path.exists(os.path.join(out, "tracked-video.avi")), "video=False writes no video")

# Without the refinement and the relocalisation, the same poses as vimlop
# track --no-refinement --no-relocalisation.
unrefined = vimlop.track_video(result=registered, frames=frames, intrinsics=intrinsics,
                               refine=False, relocalise=False)
plain = subprocess.run([program, "track", "--result", registered, "--frames", frames,
                        "--intrinsics", intrinsics, "--no-refinement", "--no-relocalisation",
                        "--no-video", "--out", "tracked-python-unrefined-cli"], check=True,
                       capture_output=True, text=True)
cli_plain = poses_of(os.path.join("tracked-python-unrefined-cli", "tracked-poses.json"))
difference = max(numpy.abs(pose - cli_plain[int(i)]).max()
                 for i, pose in zip(unrefined["frame_ids"], unrefined["camera_to_ct"]))
check(difference < 1e-6, "refine=False, relocalise=False give vimlop track --no-refinement "
      "--no-relocalisation's poses (largest difference %.2g)" % difference)

# With the electromagnetic tracker, the same poses as vimlop track --tracker
# (tracked-tip, vimlop.track.with-tracker), and a registration of it that is
# 5 mm off degrades every frame, as on the command line.
tip = vimlop.track_video(result=registered, frames=frames, intrinsics=intrinsics,
                         tracker=os.path.join(simulation, "tracker.csv"),
                         tracker_to_ct="track-tracker-in-lps.tfm")
cli_tip = poses_of(os.path.join("tracked-tip", "tracked-poses.json"))
difference = max(numpy.abs(pose - cli_tip[int(i)]).max()
                 for i, pose in zip(tip["frame_ids"], tip["camera_to_ct"]))
check(difference < 1e-6 and tip["tracking"] == 12,
      "tracker= and tracker_to_ct= give vimlop track --tracker's poses (largest difference "
      "%.2g), all 12 tracking" % difference)
off = vimlop.track_video(result=registered, frames=frames, intrinsics=intrinsics,
                         tracker=os.path.join(simulation, "tracker.csv"),
                         tracker_to_ct="track-tracker-off.tfm")
check(off["degraded"] == 12, "a tracker registered 5 mm off degrades all 12 frames (%d)"
      % off["degraded"])
try:
    vimlop.track_video(result=registered, frames=frames,
                       tracker=os.path.join(simulation, "tracker.csv"))
    check(False, "a tracker without its registration to the CT is refused")
except vimlop.TrackingError as e:
    check(str(e) == "a tracker's positions are in its own frame: give the tracker registered to "
          "the CT (--tracker-to-ct) to use them",
          "a tracker without its registration to the CT is refused: %s" % e)

# One set of defaults: vimlop track's options and the VTK source's.
text = subprocess.run([program, "track", "--help"], check=True, capture_output=True,
                      text=True).stdout
source = vimlop.vtkVIMLOPVideoTracking()
for flag, value in (("--max-features", source.GetMaxFeatures()),
                    ("--max-tracking-width-px", source.GetMaxTrackingWidthPx()),
                    ("--inlier-px", source.GetInlierThresholdPx()),
                    ("--tracker-offset-frames", source.GetTrackerOffsetFrames()),
                    ("--tracker-pull", source.GetTrackerPull()),
                    ("--tracker-max-lag-s", source.GetTrackerMaxLagS()),
                    ("--fps", source.GetFramesPerSecond())):
    match = re.search(re.escape(flag) + r" [^=\n]+=([0-9.]+)", text)
    check(match is not None and float(match.group(1)) == float(value),
          "%s: vimlop track's default is the VTK source's (%s)" % (flag, value))

# Bad input, one clear reason each.
try:
    vimlop.track_video(result=simulation, frames=frames)
    check(False, "a folder that is not a result is refused")
except vimlop.TrackingError as e:
    check(str(e) == "'%s': not a VIMLOP result folder (no result.json)" % simulation,
          "a folder that is not a result is refused: %s" % e)
try:
    vimlop.track_video(result=registered)
    check(False, "neither frames nor a camera is refused")
except ValueError as e:
    check(str(e) == "give exactly one of frames and camera",
          "neither frames nor a camera is refused: %s" % e)

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
