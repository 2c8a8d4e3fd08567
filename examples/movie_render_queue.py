"""A 30-frame camera move through the default scene, rendered offline by the render queue into PNG + EXR.

The queue (UMoviePipelineQueueEngineSubsystem, the paper's movie_render_queue: AllocateJob, SetConfiguration,
RenderJob, IsRendering) renders one output frame per engine frame while this script steps frames and draws
a progress bar from the job's progress (redrawn in place on a terminal, a line per quarter of the job when
piped). Files land in --out:

    final_color/0000.png ...                  8-bit sRGB (PNG)
    depth/, normal/, object_ids/ 0000.exr ... float32 and uint32, lossless (OpenEXR), as read_pixels() gives
    camera/0000.json ...                      K, world-to-camera, pose and samples of each frame
    final_color.mp4                           the colour frames as an H.264 video (--fps; --no-video skips it)
    preview.png                               every fifth frame's colour, side by side

Running it again resumes: frames whose files are all there are skipped (--overwrite renders them again).

    PYTHONPATH=python /usr/bin/python3 examples/movie_render_queue.py [--out out/movie_render_queue]
        [--frames 30] [--width 320 --height 240] [--path-traced --samples 16] [--overwrite] [--fps 30]
        [--no-video] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false, reportUnknownArgumentType=false

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

# By asset name: found in the working directory, SPEAR_ASSET_PATH or spear's own assets (a checkout or the
# installed package), so the example runs from anywhere.
DEFAULT_SCENE = "/Game/scenes/apartment"
M = spear.ECameraModality


def camera_move(frames: int) -> tuple[list[spear.FVector], list[spear.FRotator]]:
    """A slow dolly across the room while the camera pans from the sofa towards the window."""
    locations, rotations = [], []
    for i in range(frames):
        t = i / max(frames - 1, 1)
        ease = 0.5 - 0.5 * math.cos(math.pi * t)  # starts and stops gently
        locations.append(spear.FVector(X=-2.6 + 0.5 * ease, Y=-1.8 + 1.0 * ease, Z=1.7 - 0.1 * ease))
        rotations.append(spear.FRotator(Pitch=-18.0 + 4.0 * ease, Yaw=15.0 + 20.0 * ease))
    return locations, rotations


def progress_bar(job: spear.UMoviePipelineExecutorJob) -> str:
    p = job.GetProgress()
    done = p.FramesRendered + p.FramesSkipped
    filled = round(24 * done / max(p.FramesTotal, 1))
    eta = f", ETA {p.EstimatedSecondsLeft:.1f} s" if p.EstimatedSecondsLeft >= 0 else ""
    return f"render: [{'#' * filled}{'.' * (24 - filled)}] {done}/{p.FramesTotal} frames, {p.ElapsedSeconds:.1f} s{eta}"


def quarters_done(job: spear.UMoviePipelineExecutorJob) -> int:
    """How many quarters of the job are done (0 to 4)."""
    p = job.GetProgress()
    return 4 * (p.FramesRendered + p.FramesSkipped) // max(p.FramesTotal, 1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--out", default="out/movie_render_queue")
    parser.add_argument("--scene", default=DEFAULT_SCENE)
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--path-traced", action="store_true", help="colour from the reference path tracer")
    parser.add_argument("--samples", type=int, default=16, help="path-traced samples per pixel of each frame")
    parser.add_argument("--overwrite", action="store_true", help="render frames whose files exist again")
    parser.add_argument("--fps", type=float, default=30.0, help="the video's frames a second")
    parser.add_argument("--no-video", action="store_true", help="write no final_color.mp4")
    parser.add_argument("--server", default=None, help='None: in-process; "launch", "unix:PATH" or "tcp:HOST:PORT"')
    args = parser.parse_args()
    out = Path(args.out).resolve()  # a server may run in another directory

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=args.scene)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="MovieCamera").CameraSensor
        camera.FOV, camera.ShadowResolution = 75.0, 2048
        camera.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram  # metered, adapting as the camera moves
        if args.path_traced:
            camera.Renderer = spear.ECameraRenderer.PathTraced
        locations, rotations = camera_move(args.frames)
        queue = spear.UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem(WorldContextObject=game)
        job = queue.AllocateJob(Camera=camera, JobName="camera_move")
        job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
            OutputDirectory=str(out), Modalities=[M.FinalColor, M.Depth, M.Normal, M.ObjectIds],
            Width=args.width, Height=args.height, SamplesPerPixel=args.samples, CameraLocations=locations,
            CameraRotations=rotations, bOverwriteExisting=args.overwrite, bWriteVideo=not args.no_video,
            VideoFrameRate=args.fps))
        queue.RenderJob(Job=job)  # returns at once; the frames below do the work
    with instance.end_frame():
        pass

    # On a terminal the bar redraws in place each frame; piped into a log it is a line at each quarter.
    interactive = sys.stderr.isatty()
    logged = -1
    while True:
        with instance.begin_frame():
            pass
        with instance.end_frame():
            quarter = quarters_done(job)
            if interactive or quarter > logged or not queue.IsRendering():
                print(progress_bar(job), end="\r" if interactive else "\n", file=sys.stderr)
                logged = quarter
            if not queue.IsRendering():
                status, error, progress = job.GetStatus(), job.GetErrorMessage(), job.GetProgress()
                break
    if interactive:
        print(file=sys.stderr)
    if status != spear.EMoviePipelineJobStatus.Finished:
        sys.exit(f"movie_render_queue.py: the job ended {status.name}: {error}")
    print(f"rendered {progress.FramesRendered} frames, skipped {progress.FramesSkipped} already written, "
          f"in {progress.ElapsedSeconds:.1f} s")

    frames = sorted((out / "final_color").glob("*.png"))[::5]
    strip = np.concatenate([np.asarray(Image.open(f))[..., :3] for f in frames], axis=1)
    Image.fromarray(strip).save(out / "preview.png")
    video = "" if args.no_video else f", {out / 'final_color.mp4'}"
    print(f"wrote {out}/{{final_color,depth,normal,object_ids,camera}}/{video} and {out / 'preview.png'}")
    instance.close()


if __name__ == "__main__":
    main()
