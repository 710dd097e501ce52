"""VIMLOP's VTK classes in Python: V-IMLOP video-CT registration for VTK pipelines.

    import vimlop
    result = vimlop.register_video(ct="Cranium.inv3", frames="sim/frames",
                                   intrinsics="sim/intrinsics.yaml", tracker="sim/tracker.csv")
    result["camera_to_ct"]          # (n, 4, 4) numpy array, one pose per registered frame
    result["flagged_as_failure"]    # True: do not navigate with it
    tracked = vimlop.track_video(result="register-out", frames="sim/frames",
                                 intrinsics="sim/intrinsics.yaml")
    tracked["camera_to_ct"][tracked["states"] != "lost"]   # the poses to show

register_video() runs the main job (what `vimlop register` does, with the
same defaults) and returns numpy arrays; track_video() follows the endoscope
frame by frame after it (what `vimlop track` does). vtkVIMLOPVideoRegistration
and vtkVIMLOPVideoTracking are the same jobs as VTK sources; vtkVIMLOPRegistration (the registration filter
with a live GetTransform()) and vtkVIMLOPCTReader (CT volumes through ITK
and InVesalius projects) work with the classes of VTK's own Python package,
`vtkmodules`. The layouts of the inputs and outputs are in
Documentation/Embedding.md.
"""

# VTK's modules that hold the base classes and argument types come first, so
# that the wrapped classes find them.
from vtkmodules import vtkCommonCore, vtkCommonDataModel  # noqa: F401
from vtkmodules import vtkCommonExecutionModel, vtkCommonTransforms  # noqa: F401

from .VIMLOPImaging import vtkVIMLOPCTReader  # noqa: F401
from .VIMLOPRegistration import vtkVIMLOPRegistration  # noqa: F401
from .VIMLOPPipeline import vtkVIMLOPVideoRegistration, vtkVIMLOPVideoTracking  # noqa: F401

__all__ = ["vtkVIMLOPCTReader", "vtkVIMLOPRegistration", "vtkVIMLOPVideoRegistration",
           "vtkVIMLOPVideoTracking", "register_video", "track_video"]


class RegistrationError(RuntimeError):
    """The registration could not run (bad input, too little SfM, no start inside the airway)."""


class TrackingError(RuntimeError):
    """Tracking could not start or go on (not a result, a flagged one, frames of another camera)."""


def _run_source(source, error_class):
    """Updates a VIMLOP VTK source; raises error_class with the last error it reported."""
    import re

    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.vtkConstants import VTK_STRING

    errors = []

    @calldata_type(VTK_STRING)
    def on_error(caller, event, text):
        errors.append(text or "failed")

    source.AddObserver("ErrorEvent", on_error)
    source.Update()
    if errors:
        # The last line of VTK's message, without its "vtkClass (0x...): " prefix.
        last = errors[-1].strip().split("\n")[-1]
        raise error_class(re.sub(r"^vtk\w+ \(0x[0-9a-fA-F]+\): ", "", last))


def register_video(frames, intrinsics, ct=None, mesh=None, tracker=None, scale=0.0,
                   fps=0.0, time_offset_s=0.0, colmap=None, start_poses=None,
                   manual_start=False, threads=0, tracker_transform=None, sfm=None,
                   contours=None, tracker_to_ct=None):
    """Registers a video sequence to a CT: the main job, with `vimlop register`'s defaults.

    frames: a folder of pictures, a video file or a tracked sequence (PLUS or
    Slicer .igs.mha, with its timestamps); intrinsics: OpenCV YAML/JSON/XML;
    ct (a CT volume whose airway is segmented) or mesh (the airway surface, CT
    frame, normals into the air); tracker (CSV time_s,x_mm,y_mm,z_mm, with
    qw,qx,qy,qz for a 6-DOF sensor, or a
    tracked sequence with tracker_transform, e.g. "ProbeToTracker", which
    alone reads the tracker from the frames' file) or scale (mm per SfM unit)
    for the initial scale; tracker_to_ct: the tracker registered to the
    patient as 3D Slicer saves its TrackerToRAS transform (ITK .tfm/.h5), so
    that the tracked camera (a 6-DOF sensor: a tracked sequence or a CSV
    with qw,qx,qy,qz) turns the canonical starts (a rotation prior); fps
    overrides the frames' own timestamps or video
    rate (0: them, else 30 fps); colmap: a COLMAP sparse model
    folder instead of the built-in SfM; sfm, contours: the outputs of `vimlop
    sfm` and `vimlop contours`, reused instead of computing them; start_poses: a FramePose JSON file of
    canonical poses (default: generated along the airway) or, with
    manual_start, the camera-to-CT pose of one frame.

    Returns a dict of numpy arrays and numbers: "frame_ids" (n,), "camera_to_ct"
    (n, 4, 4; camera x right, y down, z forward; mm, CT frame LPS),
    "contour_error_px" (n,), "sfm_to_ct" (4, 4, a similarity), "flagged_as_failure",
    "mean_contour_error_px", "residual_error_mm", "candidates".
    Raises RegistrationError with the reason when the registration cannot run.
    """
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if (ct is None) == (mesh is None):
        raise ValueError("give exactly one of ct and mesh")
    registration = vtkVIMLOPVideoRegistration()
    registration.SetFramesPath(str(frames))
    registration.SetIntrinsicsFileName(str(intrinsics))
    registration.SetMeshFileName(str(mesh) if mesh is not None else "")
    registration.SetCTFileName(str(ct) if ct is not None else "")
    registration.SetTrackerFileName(str(tracker) if tracker is not None else "")
    registration.SetTrackerTransformName(str(tracker_transform) if tracker_transform else "")
    registration.SetTrackerToCTFileName(str(tracker_to_ct) if tracker_to_ct is not None else "")
    registration.SetInitialScale(float(scale))
    registration.SetFramesPerSecond(float(fps))
    registration.SetTimeOffset(float(time_offset_s))
    registration.SetColmapFolder(str(colmap) if colmap is not None else "")
    registration.SetSfmFileName(str(sfm) if sfm is not None else "")
    registration.SetContoursFileName(str(contours) if contours is not None else "")
    registration.SetStartPosesFileName(str(start_poses) if start_poses is not None else "")
    registration.SetStartFromManualPose(bool(manual_start))
    registration.SetNumberOfThreads(int(threads))
    _run_source(registration, RegistrationError)

    table = registration.GetCameraPoses()
    poses = vtk_to_numpy(table.GetColumnByName("CameraToCT")).reshape(-1, 4, 4)
    matrix = registration.GetTransform().GetMatrix()
    return {
        "frame_ids": vtk_to_numpy(table.GetColumnByName("FrameId")).copy(),
        "camera_to_ct": poses.copy(),
        "contour_error_px": vtk_to_numpy(table.GetColumnByName("ContourErrorPx")).copy(),
        "sfm_to_ct": numpy.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)]),
        "flagged_as_failure": bool(registration.GetFlaggedAsFailure()),
        "mean_contour_error_px": registration.GetContourErrorPx(),
        "residual_error_mm": registration.GetResidualErrorMm(),
        "candidates": registration.GetNumberOfCandidates(),
    }


def track_video(result, frames=None, intrinsics=None, out=None, camera=-1, first_frame=-1,
                allow_flagged=False, video=True, refine=True, relocalise=True,
                tracker=None, tracker_transform=None, tracker_to_ct=None, time_offset=0.0,
                fps=None, on_frame=None):
    """Follows the endoscope frame by frame after a registration: `vimlop track`, same defaults.

    result: the result folder of `vimlop register` (or of register_video's
    command-line twin): tracking starts on its last registered frame. frames:
    a folder of pictures, a video file or a tracked sequence, tracked from the
    frame after the registered one (first_frame: from this index); or camera,
    the index N of a V4L2 camera /dev/videoN. intrinsics: the file given to
    register (the frames are undistorted with its lens). out: a folder for
    tracked-poses.json and .vtt, tracking.json and (video=True)
    tracked-video.avi; None writes nothing. allow_flagged: track from a
    result the registration flagged as a failure (refused otherwise).
    refine: correct the tracked poses with the contours of the last frames
    against the CT (as `vimlop track` does; False: `--no-refinement`).
    relocalise: search for the pose against the CT after the tracker was
    lost, when the contours disagree with the model (False:
    `--no-relocalisation`).
    tracker: the electromagnetic tracker's recording of the scope's tip (a
    CSV, with qw,qx,qy,qz for a 6-DOF sensor's rotation, or a tracked
    sequence with tracker_transform), with tracker_to_ct, the tracker
    registered to the CT (3D Slicer's TrackerToRAS file): its tip (and a
    6-DOF sensor's rotation) at each frame's time is the prediction after a
    lost frame, and a pose more than 3 mm from it (or turned more than 5
    degrees from the sensor) is degraded (`--tracker`, `--tracker-to-ct`);
    its lag behind the frames is measured from the video's motion (its
    frames not lost) and its readings taken that much later, as `vimlop
    track` does.
    Frame id i is at time_offset + (i - the first id) / fps on its clock
    (fps: the frames' rate, `--fps`; None: vimlop track's default).
    on_frame(frame_id, state, camera_to_ct): called as each pose is
    computed; return True from it to stop after that frame.

    Returns a dict: "frame_ids" (n,), "camera_to_ct" (n, 4, 4; camera x
    right, y down, z forward; mm, CT frame), "states" (n,) of "tracking",
    "degraded" or "lost" (a lost frame's pose is the prediction: do not show
    it), "latency_ms" (n,), "contour_error_px" (n,: each frame's contours
    checked against the CT at its pose, the median distance to the model's,
    NaN where none matched), and the counts "tracking", "degraded", "lost".
    Raises TrackingError with the reason when tracking cannot start, or
    when a frame cannot be read mid-way (after tracking the frames before it).
    """
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if (frames is None) == (camera < 0):
        raise ValueError("give exactly one of frames and camera")
    tracking = vtkVIMLOPVideoTracking()
    tracking.SetResultFolder(str(result))
    tracking.SetFramesPath(str(frames) if frames is not None else "")
    tracking.SetCameraIndex(int(camera))
    tracking.SetIntrinsicsFileName(str(intrinsics) if intrinsics is not None else "")
    tracking.SetOutputFolder(str(out) if out is not None else "")
    tracking.SetWriteVideo(bool(video))
    tracking.SetFirstFrameIndex(int(first_frame))
    tracking.SetAllowFlagged(bool(allow_flagged))
    tracking.SetRefineAgainstCT(bool(refine))
    tracking.SetRelocalise(bool(relocalise))
    tracking.SetTrackerFileName(str(tracker) if tracker is not None else "")
    tracking.SetTrackerTransformName(str(tracker_transform) if tracker_transform is not None else "")
    tracking.SetTrackerToCTFileName(str(tracker_to_ct) if tracker_to_ct is not None else "")
    tracking.SetTrackerTimeOffset(float(time_offset))
    if fps is not None:
        tracking.SetFramesPerSecond(float(fps))
    if on_frame is not None:
        def on_update(caller, event):
            matrix = caller.GetCameraTransform().GetMatrix()
            pose = numpy.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
            if on_frame(caller.GetLastFrameId(), caller.GetLastFrameState(), pose):
                caller.SetAbortExecute(1)

        tracking.AddObserver("UpdateEvent", on_update)
    _run_source(tracking, TrackingError)

    table = tracking.GetTrackedPoses()
    states = table.GetColumnByName("State")
    return {
        "frame_ids": vtk_to_numpy(table.GetColumnByName("FrameId")).copy(),
        "camera_to_ct": vtk_to_numpy(table.GetColumnByName("CameraToCT")).reshape(-1, 4, 4).copy(),
        "states": numpy.array([states.GetValue(i) for i in range(states.GetNumberOfValues())]),
        "latency_ms": vtk_to_numpy(table.GetColumnByName("LatencyMs")).copy(),
        "contour_error_px": vtk_to_numpy(table.GetColumnByName("ContourErrorPx")).copy(),
        "tracking": tracking.GetNumberOfTrackingFrames(),
        "degraded": tracking.GetNumberOfDegradedFrames(),
        "lost": tracking.GetNumberOfLostFrames(),
    }
