// Video: the face tracker, temporal evidence accumulation, video sources, the vision pipeline
// and its threaded runner.
#include "common.hpp"
#include "facesocial/evidence_accumulator.hpp"
#include "facesocial/face_tracker.hpp"
#include "facesocial/pipeline_runner.hpp"
#include "facesocial/video_source.hpp"
#include "facesocial/vision_pipeline.hpp"

namespace facesocial::python {

namespace {

Frame frame_from(const py::array& image, long long index, double timestamp, cv::Mat& keep) {
    keep = mat_from_array(image, ArrayKind::Image, "VisionPipeline.process");
    Frame f;
    f.image = keep;
    f.index = index;
    f.timestamp = timestamp;
    return f;
}

}  // namespace

void bind_video(py::module_& m) {
    // --- tracker -------------------------------------------------------------------------------
    ParamsClass<TrackerParams>(m, "TrackerParams", "Parameters of the face tracker.")
        .field("min_iou", &TrackerParams::min_iou, "IoU with the predicted box that allows association")
        .field("max_center_distance", &TrackerParams::max_center_distance, "... or centre distance, share of box width")
        .field("appearance_weight", &TrackerParams::appearance_weight, "weight of appearance in the cost (0 = off)")
        .field("max_missed", &TrackerParams::max_missed, "frames a track coasts without a detection")
        .field("velocity_smoothing", &TrackerParams::velocity_smoothing, "in [0, 1)")
        .field("appearance_smoothing", &TrackerParams::appearance_smoothing, "in [0, 1)")
        .done();
    py::class_<Track>(m, "Track", "The state of one track.")
        .def_readonly("id", &Track::id)
        .def_property_readonly("box", [](const Track& t) { return tuple_from_rect(t.box); })
        .def_property_readonly("velocity", [](const Track& t) { return py::make_tuple(t.velocity.x, t.velocity.y); })
        .def_readonly("age", &Track::age)
        .def_readonly("hits", &Track::hits)
        .def_readonly("missed", &Track::missed)
        .def("__repr__", [](const Track& t) {
            return "Track(" + std::to_string(t.id) + ", missed=" + std::to_string(t.missed) + ")";
        });
    py::class_<TrackerUpdate>(m, "TrackerUpdate", "What one tracker update did.")
        .def_readonly("track_of", &TrackerUpdate::track_of, "per input face: its track id")
        .def_readonly("started", &TrackerUpdate::started)
        .def_readonly("ended", &TrackerUpdate::ended);
    py::class_<FaceTracker>(m, "FaceTracker", "Multi-face tracker for one video stream.")
        .def(py::init<const TrackerParams&>(), py::arg("params") = TrackerParams{})
        .def_property("params", &FaceTracker::params, &FaceTracker::set_params)
        .def(
            "update",
            [](FaceTracker& t, const std::vector<py::tuple>& boxes, const std::optional<std::vector<py::array>>& faces) {
                std::vector<TrackerInput> in(boxes.size());
                for (std::size_t i = 0; i < boxes.size(); ++i) in[i].box = rect_from_tuple(boxes[i], "FaceTracker.update");
                if (faces) {
                    if (faces->size() != boxes.size())
                        throw std::invalid_argument("FaceTracker.update: expected one face per box, got " +
                                                    std::to_string(faces->size()) + " for " + std::to_string(boxes.size()));
                    for (std::size_t i = 0; i < in.size(); ++i)
                        in[i].appearance = appearance_signature(mat_from_array((*faces)[i], ArrayKind::Grey, "FaceTracker.update"));
                }
                return t.update(in);
            },
            py::arg("boxes"), py::arg("faces") = py::none(),
            "Advances one frame with the (x, y, w, h) boxes found in it and, optionally, their normalised faces "
            "(for appearance).")
        .def_property_readonly("tracks", &FaceTracker::tracks)
        .def("reset", &FaceTracker::reset);

    // --- accumulation --------------------------------------------------------------------------
    py::enum_<AccumulationMode>(m, "AccumulationMode", "How frames are combined.")
        .value("MOVING_AVERAGE", AccumulationMode::MovingAverage)
        .value("EXPONENTIAL_DECAY", AccumulationMode::ExponentialDecay)
        .value("MAJORITY_VOTE", AccumulationMode::MajorityVote);
    ParamsClass<AccumulatorParams>(m, "AccumulatorParams", "Parameters of the evidence accumulator.")
        .field("mode", &AccumulatorParams::mode, "moving average (the paper), exponential decay, majority vote")
        .field("window", &AccumulatorParams::window, "frames in the window")
        .field("decay", &AccumulatorParams::decay, "exponential decay: weight kept by the past per frame")
        .done();
    py::class_<EvidenceAccumulator>(m, "EvidenceAccumulator", "Accumulates one track's score vectors.")
        .def(py::init<const AccumulatorParams&>(), py::arg("params") = AccumulatorParams{})
        .def_property_readonly("params", &EvidenceAccumulator::params)
        .def("add", &EvidenceAccumulator::add, py::arg("scores"))
        .def_property_readonly("frames", &EvidenceAccumulator::frames)
        .def("reset", &EvidenceAccumulator::reset)
        .def("accumulated", &EvidenceAccumulator::accumulated)
        .def("decide", &EvidenceAccumulator::decide, py::arg("rule") = UnknownRule{});

    // --- sources, pipeline, runner -------------------------------------------------------------
    py::enum_<FrameStatus>(m, "FrameStatus")
        .value("OK", FrameStatus::Ok)
        .value("SKIPPED", FrameStatus::Skipped)
        .value("END", FrameStatus::End)
        .value("LOST", FrameStatus::Lost);
    py::class_<VideoSource, std::shared_ptr<VideoSource>>(m, "VideoSource", "Camera index, video file, URL or frame folder.")
        .def_static(
            "open", [](const std::string& spec) { return std::shared_ptr<VideoSource>(VideoSource::open(spec)); },
            py::arg("spec"), "Raises FileError when it cannot be opened.")
        .def(
            "read",
            [](VideoSource& s) {
                Frame f;
                FrameStatus st;
                {
                    py::gil_scoped_release release;
                    st = s.read(f);
                }
                return py::make_tuple(st, f.image.empty() ? py::object(py::none()) : py::object(array_from_mat(f.image)),
                                      f.index, f.timestamp, f.message);
            },
            "(status, image or None, index, timestamp, message)")
        .def_property_readonly("is_live", &VideoSource::is_live)
        .def_property_readonly("frame_count", &VideoSource::frame_count)
        .def_property_readonly("fps", &VideoSource::fps)
        .def_property_readonly("description", &VideoSource::description);

    ParamsClass<PipelineParams>(m, "PipelineParams", "Everything that shapes the vision pipeline.")
        .field("front_end", &PipelineParams::front_end, "detection, skin filter, normalisation")
        .field("tracker", &PipelineParams::tracker, "association across frames")
        .field("accumulator", &PipelineParams::accumulator, "evidence per track")
        .field("use_appearance", &PipelineParams::use_appearance, "appearance in the association cost")
        .field("use_bank_rule", &PipelineParams::use_bank_rule, "apply the bank's unknown rule")
        .field("unknown", &PipelineParams::unknown, "the rule when use_bank_rule is False")
        .field("min_frames", &PipelineParams::min_frames, "frames of evidence before a decision event")
        .done();
    py::class_<TrackReport>(m, "TrackReport", "One face track after a frame.")
        .def_readonly("track_id", &TrackReport::track_id)
        .def_readonly("detection", &TrackReport::detection)
        .def_readonly("seen", &TrackReport::seen)
        .def_readonly("missed", &TrackReport::missed)
        .def_readonly("frames", &TrackReport::frames)
        .def_readonly("decision", &TrackReport::decision, "from the accumulated scores")
        .def_readonly("frame_decision", &TrackReport::frame_decision, "from this frame alone")
        .def("__repr__", [](const TrackReport& t) {
            return "TrackReport(" + std::to_string(t.track_id) + ", " + (t.decision.known ? t.decision.name : "unknown") +
                   ", frames=" + std::to_string(t.frames) + ")";
        });
    py::enum_<PipelineEventKind>(m, "PipelineEventKind")
        .value("TRACK_STARTED", PipelineEventKind::TrackStarted)
        .value("DECISION_MADE", PipelineEventKind::DecisionMade)
        .value("DECISION_CHANGED", PipelineEventKind::DecisionChanged)
        .value("TRACK_LOST", PipelineEventKind::TrackLost)
        .value("FRAME_SKIPPED", PipelineEventKind::FrameSkipped)
        .value("STREAM_ENDED", PipelineEventKind::StreamEnded)
        .value("SOURCE_LOST", PipelineEventKind::SourceLost);
    py::class_<PipelineEvent>(m, "PipelineEvent")
        .def_readonly("kind", &PipelineEvent::kind)
        .def_readonly("frame", &PipelineEvent::frame)
        .def_readonly("timestamp", &PipelineEvent::timestamp)
        .def_readonly("track_id", &PipelineEvent::track_id)
        .def_readonly("name", &PipelineEvent::name)
        .def_readonly("previous", &PipelineEvent::previous)
        .def_readonly("score", &PipelineEvent::score)
        .def_readonly("frames", &PipelineEvent::frames)
        .def_readonly("message", &PipelineEvent::message)
        .def("__repr__", [](const PipelineEvent& e) {
            return "PipelineEvent(" + to_string(e.kind) + ", frame=" + std::to_string(e.frame) +
                   (e.track_id ? ", track=" + std::to_string(e.track_id) : std::string()) + ")";
        });
    py::class_<PipelineResult>(m, "PipelineResult", "The outcome of one frame or stream status.")
        .def_readonly("frame", &PipelineResult::frame)
        .def_readonly("timestamp", &PipelineResult::timestamp)
        .def_readonly("status", &PipelineResult::status)
        .def_property_readonly("image", [](const PipelineResult& r) {
            return r.image.empty() ? py::object(py::none()) : py::object(array_from_mat(r.image));
        })
        .def_readonly("tracks", &PipelineResult::tracks)
        .def_readonly("events", &PipelineResult::events)
        .def_readonly("faces_detected", &PipelineResult::faces_detected)
        .def_readonly("front_end_ms", &PipelineResult::front_end_ms)
        .def_readonly("scoring_ms", &PipelineResult::scoring_ms)
        .def_readonly("total_ms", &PipelineResult::total_ms);
    py::class_<VisionPipeline, std::shared_ptr<VisionPipeline>>(m, "VisionPipeline",
                                                                "frame -> faces -> scores -> tracks -> decisions.")
        .def(py::init<std::shared_ptr<const ClassifierBank>, const PipelineParams&>(), py::arg("bank"),
             py::arg("params") = PipelineParams{})
        .def(
            "process",
            [](VisionPipeline& p, const py::array& image, long long index, double timestamp) {
                cv::Mat keep;
                const Frame f = frame_from(image, index, timestamp, keep);
                py::gil_scoped_release release;
                return p.process(f);
            },
            py::arg("image"), py::arg("index") = -1, py::arg("timestamp") = 0.0, "Processes one uint8 grey or BGR frame.")
        .def_property("params", &VisionPipeline::params, &VisionPipeline::set_params,
                      "Read or change (applies from the next frame) while running.")
        .def("snapshot", &VisionPipeline::snapshot, "The latest frame's result.")
        .def(
            "face_regions",
            [](const VisionPipeline& p) {
                py::list out;
                for (const cv::Rect& r : p.face_regions()) out.append(tuple_from_rect(r));
                return out;
            },
            "(x, y, w, h) boxes of the latest frame's faces.");

    ParamsClass<RunnerParams>(m, "RunnerParams", "Queues of the threaded runner.")
        .field("frame_queue", &RunnerParams::frame_queue, "frames waiting for processing")
        .field("result_queue", &RunnerParams::result_queue, "results waiting; the oldest is dropped when full")
        .field("drop_frames", &RunnerParams::drop_frames, "-1 live sources only, 0 never, 1 always")
        .done();
    py::class_<RunnerStats>(m, "RunnerStats")
        .def_readonly("frames_read", &RunnerStats::frames_read)
        .def_readonly("frames_processed", &RunnerStats::frames_processed)
        .def_readonly("frames_dropped", &RunnerStats::frames_dropped)
        .def_readonly("results_dropped", &RunnerStats::results_dropped)
        .def_readonly("processing_fps", &RunnerStats::processing_fps);
    py::class_<PipelineRunner>(m, "PipelineRunner", "Runs a pipeline on a source in background threads.")
        .def(py::init([](std::shared_ptr<VisionPipeline> pipeline, const std::string& source, const RunnerParams& params) {
                 return std::make_unique<PipelineRunner>(std::move(pipeline), VideoSource::open(source), params);
             }),
             py::arg("pipeline"), py::arg("source"), py::arg("params") = RunnerParams{},
             "Opens `source` (camera index, file, URL, folder) and starts at once.")
        .def(
            "next",
            [](PipelineRunner& r, double timeout_s) -> std::optional<PipelineResult> {
                PipelineResult out;
                bool got;
                {
                    py::gil_scoped_release release;
                    got = r.next(out, std::chrono::milliseconds(static_cast<long long>(timeout_s * 1000)));
                }
                if (!got) return std::nullopt;
                return out;
            },
            py::arg("timeout") = 1.0, "The next result, or None on timeout / when finished.")
        .def_property_readonly("finished", &PipelineRunner::finished)
        .def("stop", &PipelineRunner::stop)
        .def_property_readonly("stats", &PipelineRunner::stats)
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", [](PipelineRunner& r) {
            PipelineResult out;
            for (;;) {
                bool got;
                {
                    py::gil_scoped_release release;
                    got = r.next(out, std::chrono::milliseconds(200));
                }
                if (got) return out;
                if (r.finished()) {
                    if (auto err = r.error()) std::rethrow_exception(err);
                    throw py::stop_iteration();
                }
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            }
        });
}

}  // namespace facesocial::python
