"""The video pipeline from Python: the Hamilton clip through the threaded runner, a frame at a
time with parameter changes, the tracker and the accumulator."""

import numpy as np
import pytest

import facesocial as fs


@pytest.fixture(scope="module")
def bank(orl):
    b = fs.ClassifierBank()
    for name, faces in zip(orl.names[:4], orl.faces[:4]):
        b.add_faces(name, faces[:3])
    b.train()
    return b


def test_runner_on_the_real_clip_yields_tracks_and_events(bank, data):
    pipeline = fs.VisionPipeline(bank)
    runner = fs.PipelineRunner(pipeline, str(data / "video_hamilton" / "short_hamilton_clip.mp4"),
                               fs.RunnerParams(result_queue=1000))
    results = list(runner)
    assert runner.finished and runner.stats.frames_processed == 275
    assert results[-1].status == fs.FrameStatus.END and results[-1].image is None
    assert results[100].image.shape == (360, 640, 3)
    kinds = [e.kind for r in results for e in r.events]
    assert kinds.count(fs.PipelineEventKind.TRACK_STARTED) >= 2
    assert kinds.count(fs.PipelineEventKind.TRACK_STARTED) == kinds.count(fs.PipelineEventKind.TRACK_LOST)
    seen = [t for r in results for t in r.tracks if t.seen]
    assert seen and all(len(t.frame_decision.ranked) == 4 for t in seen)


def test_frames_one_at_a_time_and_parameters_while_running(bank, data):
    source = fs.VideoSource.open(str(data / "video_hamilton" / "short_hamilton_clip.mp4"))
    assert not source.is_live and source.frame_count == 275
    pipeline = fs.VisionPipeline(bank)
    for _ in range(120):
        status, image, index, timestamp, _ = source.read()
    assert status == fs.FrameStatus.OK and image.dtype == np.uint8
    result = pipeline.process(image, index, timestamp)
    assert result.frame == index and pipeline.snapshot().frame == index
    assert len(pipeline.face_regions()) == sum(t.seen for t in result.tracks)
    params = pipeline.params
    params.accumulator.window = 5
    pipeline.params = params
    assert pipeline.params.accumulator.window == 5
    with pytest.raises(ValueError):
        pipeline.params = fs.PipelineParams(min_frames=0)
    with pytest.raises(ValueError, match="VisionPipeline.process"):
        pipeline.process(image.astype(np.float32))
    with pytest.raises(fs.FileError, match="camera 7"):
        fs.VideoSource.open("7")


def test_tracker_and_accumulator(orl):
    tracker = fs.FaceTracker(fs.TrackerParams(max_missed=2))
    first = tracker.update([(10, 10, 50, 50), (200, 10, 50, 50)], [orl.faces[0][0], orl.faces[1][0]])
    assert len(first.started) == 2
    second = tracker.update([(205, 10, 50, 50), (12, 10, 50, 50)])
    assert second.track_of == [first.track_of[1], first.track_of[0]]
    with pytest.raises(ValueError, match="one face per box"):
        tracker.update([(0, 0, 5, 5)], [])
    acc = fs.EvidenceAccumulator(fs.AccumulatorParams(window=2))
    acc.add(fs.BankScores(["ann", "bob"], [-10.0, -12.0]))
    acc.add(fs.BankScores(["ann", "bob"], [-14.0, -11.0]))
    acc.add(fs.BankScores(["ann", "bob"], [-12.0, -13.0]))
    assert list(acc.accumulated().scores) == [-13.0, -12.0]
    assert acc.decide().name == "bob" and acc.frames == 2
