"""The offline render queue (UMoviePipelineQueueEngineSubsystem): jobs render a camera through poses or
through the running world's frames into PNG + EXR + camera JSON files (and final_color as an MP4 video), one
output frame per engine frame, with progress, cancel, resume and clear errors; both transports."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images
from spear.errors import InvalidArgumentError, InvalidStateError

M = spear.ECameraModality
Status = spear.EMoviePipelineJobStatus
MODALITIES = [M.FinalColor, M.HdrColor, M.Depth, M.Normal, M.ObjectIds]


def _scene(game: spear.UWorld) -> spear.UCameraSensorComponent:
    """A lit box on a ground plane, and a 40 x 30 camera looking at it."""
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.SetActorScale3D(NewScale3D=spear.FVector(X=20.0, Y=20.0, Z=1.0))
    box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box", location=spear.FVector(Z=0.5))
    box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                              location=spear.FVector(X=-4.0, Z=1.5)).CameraSensor
    camera.Width, camera.Height, camera.FOV = 40, 30, 70.0
    camera.Modalities = [M.FinalColor]
    return camera


def _poses(count: int) -> tuple[list[spear.FVector], list[spear.FRotator]]:
    """A camera move around the box: each pose looks at it from another side."""
    locations, rotations = [], []
    for i in range(count):
        yaw = 40.0 * i
        a = np.radians(yaw)
        locations.append(spear.FVector(X=-4.0 * float(np.cos(a)), Y=-4.0 * float(np.sin(a)), Z=1.5))
        rotations.append(spear.FRotator(Pitch=-15.0, Yaw=yaw))
    return locations, rotations


def _queue(game: spear.UWorld) -> spear.UMoviePipelineQueueEngineSubsystem:
    return spear.UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem(WorldContextObject=game)


def _configuration(out: Path, poses: int, **fields: object) -> spear.FMoviePipelineConfiguration:
    locations, rotations = _poses(poses)
    config = spear.FMoviePipelineConfiguration(OutputDirectory=str(out), Modalities=MODALITIES, Width=48,
                                               Height=32, CameraLocations=locations, CameraRotations=rotations)
    for name, value in fields.items():
        setattr(config, name, value)
    return config


def _render(instance: spear.Instance, queue: spear.UMoviePipelineQueueEngineSubsystem, limit: int = 50) -> int:
    """Steps frames until the queue is idle; returns how many frames that took."""
    for frames in range(1, limit + 1):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            if not queue.IsRendering():
                return frames
    raise AssertionError(f"the queue still renders after {limit} frames")


def test_a_job_writes_every_frame_equal_to_read_pixels_and_puts_the_camera_back(
    instance: spear.Instance, tmp_path: Path
) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera, JobName="orbit")
        assert job.GetStatus() == Status.Unconfigured and job.JobName == "orbit"
        job.SetConfiguration(Configuration=_configuration(tmp_path, 3))
        assert job.GetStatus() == Status.Ready
        queue.RenderJob(Job=job)  # returns at once: the work is done by the frames that follow
        assert job.GetStatus() == Status.Queued and queue.IsRendering()
    with instance.end_frame():
        assert job.GetStatus() == Status.Rendering and queue.GetActiveJob() == job
        # The frame RenderJob was called in rendered frame 0; its files are written while the next frames
        # render.
        progress = job.GetProgress()
        assert progress.FramesRendered + progress.FramesWriting == 1
    _render(instance, queue)

    with instance.begin_frame():
        progress = job.GetProgress()
        assert job.GetStatus() == Status.Finished and not queue.IsRendering() and queue.GetActiveJob() is None
        assert (progress.FramesTotal, progress.FramesRendered, progress.FramesSkipped) == (3, 3, 0)
        assert progress.FramesWriting == 0  # a job ends when its files are on disk
        assert progress.EstimatedSecondsLeft == 0.0 and progress.ElapsedSeconds > 0.0
        # The camera is as it was before the job.
        assert (camera.Width, camera.Height, camera.Modalities, camera.Latency) == (40, 30, [M.FinalColor], 0)
        assert camera.GetComponentLocation() == spear.FVector(X=-4.0, Z=1.5)
        files = job.GetOutputFiles(Frame=1)
        assert [Path(f).relative_to(tmp_path).as_posix() for f in files] == [
            "final_color/0001.png", "hdr_color/0001.exr", "depth/0001.exr", "normal/0001.exr",
            "object_ids/0001.exr", "camera/0001.json"]
        # The same pose and settings by hand: the files hold exactly what read_pixels() returns.
        locations, rotations = _poses(3)
        camera.Width, camera.Height, camera.Modalities = 48, 32, MODALITIES
        camera.SetWorldLocation(NewLocation=locations[1])
        camera.SetWorldRotation(NewRotation=rotations[1])
    with instance.end_frame():
        pixels = camera.read_pixels()
        K, T = camera.GetIntrinsicMatrix(), camera.GetWorldToCamera()
    assert "final_color" in pixels and "hdr_color" in pixels and "depth" in pixels
    assert "normal" in pixels and "object_ids" in pixels
    png = np.asarray(Image.open(files[0]))
    assert png.dtype == np.uint8 and np.array_equal(png, pixels["final_color"])
    for file, key in zip(files[1:5], ["hdr_color", "depth", "normal", "object_ids"]):
        image = spear.images.read_exr(file)
        expected = pixels[key]  # type: ignore[literal-required]
        assert image.dtype == expected.dtype and image.shape == expected.shape, key
        assert np.array_equal(image, expected), key
    record = json.loads(Path(files[5]).read_text())
    assert record["frame"] == 1 and (record["width"], record["height"]) == (48, 32)
    assert record["distortion_coefficients"] == [0.0] * 5
    assert np.allclose(record["intrinsic_matrix"], K) and np.allclose(record["world_to_camera"], T)
    assert record["renderer"] == "raster"
    assert (pixels["object_ids"] > 0).any()  # the box and the ground are in view


def test_a_job_run_again_skips_the_frames_already_written(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera)
        job.SetConfiguration(Configuration=_configuration(tmp_path, 4, Modalities=[M.FinalColor, M.Depth]))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    # Files are written to a new file renamed into place: a rewritten one has another inode or modification
    # time (an inode number alone may be reused for the new file).
    written = {f: (os.stat(f).st_ino, os.stat(f).st_mtime_ns) for f in tmp_path.rglob("*") if f.is_file()}
    assert len(written) == 4 * 3
    (tmp_path / "depth" / "0002.exr").unlink()  # frame 2 is no longer whole

    with instance.begin_frame():
        queue.RenderJob(Job=job)  # a finished job may be queued again
    with instance.end_frame():
        pass
    frames = _render(instance, queue)
    with instance.begin_frame():
        progress = job.GetProgress()
        assert job.GetStatus() == Status.Finished
        assert (progress.FramesRendered, progress.FramesSkipped) == (1, 3)
    with instance.end_frame():
        pass
    assert frames == 1  # the poses of finished frames cost no engine frame
    again = {f: (os.stat(f).st_ino, os.stat(f).st_mtime_ns) for f in tmp_path.rglob("*") if f.is_file()}
    changed = sorted(f.relative_to(tmp_path).as_posix() for f in again if again[f] != written.get(f))
    assert changed == ["camera/0002.json", "depth/0002.exr", "final_color/0002.png"]

    # bOverwriteExisting renders every frame again.
    with instance.begin_frame():
        job.SetConfiguration(Configuration=_configuration(
            tmp_path, 4, Modalities=[M.FinalColor, M.Depth], bOverwriteExisting=True, FrameStart=1, FrameEnd=3))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        progress = job.GetProgress()
        assert (progress.FramesTotal, progress.FramesRendered, progress.FramesSkipped) == (2, 2, 0)
    with instance.end_frame():
        pass


def _mp4_video(path: Path) -> tuple[str, int, int, int]:
    """(codec, frames, width, height) of an MP4 file's one video track, read from its boxes: the sample
    entry of stsd and the sample count of stsz."""
    data = path.read_bytes()
    assert data[4:8] == b"ftyp"

    def boxes(start: int, end: int) -> dict[bytes, tuple[int, int]]:
        found: dict[bytes, tuple[int, int]] = {}
        while start + 8 <= end:
            size, kind = int.from_bytes(data[start:start + 4], "big"), data[start + 4:start + 8]
            found.setdefault(kind, (start + 8, start + size))
            start += size
        return found

    box = boxes(0, len(data))[b"moov"]
    for kind in (b"trak", b"mdia", b"minf", b"stbl"):
        box = boxes(*box)[kind]
    table = boxes(*box)
    entry = table[b"stsd"][0] + 8  # after version, flags and the entry count
    codec = data[entry + 4:entry + 8].decode()
    width, height = int.from_bytes(data[entry + 32:entry + 34], "big"), int.from_bytes(data[entry + 34:entry + 36], "big")
    frames = int.from_bytes(data[table[b"stsz"][0] + 8:table[b"stsz"][0] + 12], "big")
    return codec, frames, width, height


def test_a_job_writes_final_color_as_a_video_of_every_frame(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera, JobName="clip")
        job.SetConfiguration(Configuration=_configuration(tmp_path, 5, Modalities=[M.FinalColor, M.Depth],
                                                          Width=49, bWriteVideo=True, VideoFrameRate=10.0))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        assert job.GetStatus() == Status.Finished, job.GetErrorMessage()
    with instance.end_frame():
        pass
    video = tmp_path / "final_color.mp4"
    assert _mp4_video(video) == ("avc1", 5, 50, 32)  # an odd width padded by one column
    first = video.stat().st_mtime_ns

    # A job run again after a frame was lost renders that frame and writes the video again, of every frame.
    (tmp_path / "final_color" / "0003.png").unlink()
    with instance.begin_frame():
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        assert job.GetStatus() == Status.Finished and job.GetProgress().FramesRendered == 1
    with instance.end_frame():
        pass
    assert _mp4_video(video) == ("avc1", 5, 50, 32) and video.stat().st_mtime_ns != first

    with instance.begin_frame():
        with pytest.raises(InvalidArgumentError, match=r"bWriteVideo writes final_color as a video, which "
                                                      r"Modalities leaves out"):
            job.SetConfiguration(Configuration=_configuration(tmp_path, 5, Modalities=[M.Depth], bWriteVideo=True))
        with pytest.raises(InvalidArgumentError, match=r"VideoFrameRate must be in \(0, 1000\] frames a second, "
                                                      r"got 0"):
            job.SetConfiguration(Configuration=_configuration(tmp_path, 5, VideoFrameRate=0.0))
        # Modalities left to the camera: checked when the job starts, which fails it.
        camera.Modalities = [M.Depth]
        job.SetConfiguration(Configuration=_configuration(tmp_path / "depth_only", 2, Modalities=[],
                                                          bWriteVideo=True))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        assert job.GetStatus() == Status.Failed
        assert "job 'clip' writes final_color as a video (bWriteVideo), but its camera does not render " \
               "final_color" in job.GetErrorMessage()
    with instance.end_frame():
        pass


def test_cancel_stops_a_job_and_the_queue_goes_on_to_the_next(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        first, second = queue.AllocateJob(Camera=camera), queue.AllocateJob(Camera=camera)
        assert (first.JobName, second.JobName) == ("RenderJob_0", "RenderJob_1")
        assert queue.GetJobs() == [first, second]
        first.SetConfiguration(Configuration=_configuration(tmp_path / "first", 6))
        second.SetConfiguration(Configuration=_configuration(tmp_path / "second", 2))
        queue.RenderJob(Job=first)
        queue.RenderJob(Job=second)
        with pytest.raises(InvalidStateError, match=r"RenderJob\(\): job 'RenderJob_0' is already queued"):
            queue.RenderJob(Job=first)
        with pytest.raises(InvalidStateError, match=r"SetConfiguration\(\): job 'RenderJob_1' is queued or "
                                                    r"rendering; cancel it first"):
            second.SetConfiguration(Configuration=_configuration(tmp_path, 1))
    with instance.end_frame():
        pass
    with instance.begin_frame():
        pass
    with instance.end_frame():
        progress = first.GetProgress()
        assert progress.FramesRendered + progress.FramesWriting == 2
        first.Cancel()  # waits for the frames being written
        assert (first.GetProgress().FramesRendered, first.GetProgress().FramesWriting) == (2, 0)
        assert first.GetStatus() == Status.Cancelled and second.GetStatus() == Status.Queued
        assert camera.Width == 40 and camera.GetComponentLocation() == spear.FVector(X=-4.0, Z=1.5)
        with pytest.raises(InvalidStateError, match=r"DeleteJob\(\): job 'RenderJob_1' is queued or rendering"):
            queue.DeleteJob(Job=second)
    _render(instance, queue)
    with instance.begin_frame():
        assert second.GetStatus() == Status.Finished
        assert sorted(p.name for p in (tmp_path / "first" / "depth").iterdir()) == ["0000.exr", "0001.exr"]
        queue.DeleteJob(Job=first)
        assert queue.GetJobs() == [second]
        with pytest.raises(spear.errors.StaleObjectError):
            first.GetStatus()
        queue.RenderJob(Job=second)
        queue.CancelAllJobs()
        assert second.GetStatus() == Status.Cancelled and not queue.IsRendering()
    with instance.end_frame():
        pass


def test_without_poses_a_job_records_consecutive_frames_of_the_running_world(
    instance: spear.Instance, tmp_path: Path
) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball", location=spear.FVector(Z=3.0))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        ball.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera)
        # Frames 2..4 of the recording: the first two engine frames pass unrendered.
        job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
            OutputDirectory=str(tmp_path), Modalities=[M.Depth], FrameStart=2, FrameEnd=5))
        queue.RenderJob(Job=job)
        start = game.get_frame_count()
    with instance.end_frame():
        pass
    _render(instance, queue)
    records = [json.loads((tmp_path / "camera" / f"{k:04d}.json").read_text()) for k in (2, 3, 4)]
    assert [r["engine_frame"] - start for r in records] == [3, 4, 5]
    assert not (tmp_path / "camera" / "0001.json").exists()
    depths = [spear.images.read_exr(tmp_path / "depth" / f"{k:04d}.exr") for k in (2, 3, 4)]
    assert depths[0].shape == (30, 40)  # the camera's own size
    assert not np.array_equal(depths[0], depths[2])  # the ball fell meanwhile
    with instance.begin_frame():
        progress = job.GetProgress()
        assert (progress.FramesTotal, progress.FramesRendered, progress.FramesSkipped) == (3, 3, 0)
        assert camera.Modalities == [M.FinalColor] and camera.GetComponentLocation() == spear.FVector(X=-4.0, Z=1.5)
        # Run again with frame 3 missing: frames 2 and 4 pass unrendered, frame 3 is the engine frame after.
        (tmp_path / "depth" / "0003.exr").unlink()
        queue.RenderJob(Job=job)
        start = game.get_frame_count()
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        progress = job.GetProgress()
        assert (progress.FramesRendered, progress.FramesSkipped) == (1, 2)
    with instance.end_frame():
        pass
    record = json.loads((tmp_path / "camera" / "0003.json").read_text())
    assert record["engine_frame"] - start == 4


def test_a_path_traced_frame_has_its_own_samples(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        camera.Renderer = spear.ECameraRenderer.PathTraced
        camera.MaxBounces = 1
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera)
        same = [spear.FVector(X=-4.0, Z=1.5)] * 3  # a still view would otherwise accumulate
        job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
            OutputDirectory=str(tmp_path), Modalities=[M.FinalColor, M.HdrColor], Width=16, Height=12,
            SamplesPerPixel=3, CameraLocations=same, CameraRotations=[spear.FRotator()] * 3))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    records = [json.loads((tmp_path / "camera" / f"{k:04d}.json").read_text()) for k in range(3)]
    assert [(r["renderer"], r["samples_per_pixel"]) for r in records] == [("path_traced", 3)] * 3
    hdr = [spear.images.read_exr(tmp_path / "hdr_color" / f"{k:04d}.exr") for k in range(3)]
    assert hdr[0].dtype == np.float16 and hdr[0].shape == (12, 16, 4)
    assert np.array_equal(hdr[0], hdr[2])  # each frame restarts the same sample sequence
    with instance.begin_frame():
        assert camera.SamplesPerPixel == 4  # the camera's own setting is back


def test_bad_configurations_and_jobs_are_refused_naming_the_field(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera, JobName="bad")
        with pytest.raises(InvalidStateError, match=r"RenderJob\(\): job 'bad' has no configuration; call its "
                                                    r"SetConfiguration\(\) first"):
            queue.RenderJob(Job=job)
        cases = [
            (dict(OutputDirectory=""), r"OutputDirectory is empty"),
            (dict(Width=-3), r"Width must be 0 \(the camera's\) or in \[1, 16384\], got -3"),
            (dict(SamplesPerPixel=70000), r"SamplesPerPixel must be 0 \(the camera's\) or in \[1, 65536\], got 70000"),
            (dict(CameraRotations=[]), r"CameraLocations has 3 poses and CameraRotations 0; they pair up"),
            (dict(FrameEnd=4), r"frames \[0, 4\) are not a non-empty range within the 3 poses"),
            (dict(CameraLocations=[], CameraRotations=[]), r"without CameraLocations, FrameEnd must be given"),
            (dict(CameraLocations=[spear.FVector(X=float("nan"))] * 3),
             r"CameraLocations\[0\] must be finite, got \(nan, 0, 0\)"),
        ]
        for fields, message in cases:
            with pytest.raises(InvalidArgumentError, match=r"UMoviePipelineExecutorJob.SetConfiguration\(\): "
                                                          + message):
                job.SetConfiguration(Configuration=_configuration(tmp_path, 3, **fields))
        assert job.GetStatus() == Status.Unconfigured
        with pytest.raises(InvalidArgumentError, match=r"AllocateJob\(\): argument 'Camera' must not be None"):
            queue.AllocateJob(Camera=None)  # type: ignore[arg-type]
        other = instance.create_world(name="Other")
        with pytest.raises(InvalidArgumentError, match=r"RenderJob\(\): job 'bad' belongs to another world's queue"):
            _queue(other).RenderJob(Job=job)
    with instance.end_frame():
        pass


def test_a_failing_job_is_reported_and_the_engine_goes_on(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    blocker = tmp_path / "blocked"
    blocker.write_text("a file where the output folder should be")
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        unwritable = queue.AllocateJob(Camera=camera, JobName="unwritable")
        unwritable.SetConfiguration(Configuration=_configuration(blocker, 2))
        orphan = queue.AllocateJob(Camera=camera, JobName="orphan")
        orphan.SetConfiguration(Configuration=_configuration(tmp_path / "orphan", 5))
        queue.RenderJob(Job=unwritable)
        queue.RenderJob(Job=orphan)
    with instance.end_frame():
        assert unwritable.GetStatus() == Status.Failed
        assert "cannot create folder" in unwritable.GetErrorMessage()
        assert orphan.GetStatus() == Status.Rendering  # it took the frame the first job could not use
    with instance.begin_frame():
        owner = camera.GetOwner()
        assert owner is not None
        game.destroy_actor(actor=owner)
    with instance.end_frame():
        assert orphan.GetStatus() == Status.Failed and not queue.IsRendering()
        assert orphan.GetErrorMessage() == "render job 'orphan': its camera was destroyed"
        assert orphan.GetCamera() is None
        assert orphan.GetProgress().FramesRendered == 1


def test_a_file_that_cannot_be_written_fails_the_job(instance: spear.Instance, tmp_path: Path) -> None:
    (tmp_path / "depth" / "0002.exr").mkdir(parents=True)  # where frame 2's depth file should go
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        queue = _queue(game)
        job = queue.AllocateJob(Camera=camera, JobName="blocked")
        job.SetConfiguration(Configuration=_configuration(tmp_path, 8, Modalities=[M.FinalColor, M.Depth]))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    _render(instance, queue)
    with instance.begin_frame():
        assert job.GetStatus() == Status.Failed and not queue.IsRendering()
        assert job.GetErrorMessage().startswith("render job 'blocked': EXR file '")
        assert job.GetErrorMessage().endswith("depth/0002.exr' is not a regular file (a FIFO, device or socket)")
        progress = job.GetProgress()
        assert progress.FramesWriting == 0 and progress.EstimatedSecondsLeft == -1.0
        assert not (tmp_path / "camera" / "0002.json").exists()  # frame 2 is not whole
        assert camera.Width == 40  # put back
    with instance.end_frame():
        pass


def test_poses_need_a_movable_camera(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = _scene(game)
        camera.SetMobility(NewMobility=spear.EComponentMobility.Static)
        queue = _queue(game)
        still = queue.AllocateJob(Camera=camera, JobName="still")
        still.SetConfiguration(Configuration=_configuration(tmp_path / "still", 2))
        recording = queue.AllocateJob(Camera=camera, JobName="recording")
        recording.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
            OutputDirectory=str(tmp_path / "recording"), FrameEnd=2))
        queue.RenderJob(Job=still)
        queue.RenderJob(Job=recording)
    with instance.end_frame():
        # The first job fails to start; the second takes the same frame (a static camera may record).
        assert still.GetStatus() == Status.Failed
        assert still.GetErrorMessage() == (
            "UMoviePipelineQueueEngineSubsystem.RenderJob(): job 'still' moves its camera through poses, but "
            "UCameraSensorComponent 'CameraSensor' is static; set its Mobility to Movable")
        assert recording.GetStatus() == Status.Rendering
    _render(instance, queue)
    with instance.begin_frame():
        assert recording.GetStatus() == Status.Finished
    with instance.end_frame():
        pass
