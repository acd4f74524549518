#include "facesocial/vision_pipeline.hpp"

#include <chrono>
#include <map>
#include <stdexcept>

namespace facesocial {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool same_accumulation(const AccumulatorParams& a, const AccumulatorParams& b) {
    return a.mode == b.mode && a.window == b.window && a.decay == b.decay;
}

}  // namespace

std::string to_string(PipelineEventKind kind) {
    switch (kind) {
    case PipelineEventKind::TrackStarted: return "track_started";
    case PipelineEventKind::DecisionMade: return "decision_made";
    case PipelineEventKind::DecisionChanged: return "decision_changed";
    case PipelineEventKind::TrackLost: return "track_lost";
    case PipelineEventKind::FrameSkipped: return "frame_skipped";
    case PipelineEventKind::StreamEnded: return "stream_ended";
    case PipelineEventKind::SourceLost: return "source_lost";
    }
    return "?";
}

FrontEndParams PipelineParams::default_front_end() {
    FrontEndParams p;
    p.frontal = CascadeDetectorParams::fast_frontal();
    p.profile = CascadeDetectorParams::fast_profile();
    p.use_profile = false;
    p.use_skin_filter = true;
    p.normalize = true;
    return p;
}

void PipelineParams::validate() const {
    front_end.validate();
    tracker.validate();
    accumulator.validate();
    if (!use_bank_rule) unknown.validate();
    if (min_frames < 1 || min_frames > 100000)
        throw std::invalid_argument("PipelineParams: expected min_frames in [1, 100000], got " + std::to_string(min_frames));
    if (!front_end.normalize)
        throw std::invalid_argument("PipelineParams: expected front_end.normalize on (faces are scored), got off");
}

/// Per-stream state, touched only under process_mutex_.
struct VisionPipeline::State {
    PipelineParams params;          // in use
    std::unique_ptr<FrontEnd> front_end;
    FaceTracker tracker;
    struct TrackEvidence {
        EvidenceAccumulator accumulator;
        bool reported = false;
        std::string reported_name;  // "" = unknown
        Detection detection;
    };
    std::map<int, TrackEvidence> evidence;
    PipelineResult last;

    // Pending parameters from set_params (under params_mutex_).
    PipelineParams pending;
    bool has_pending = false;
};

VisionPipeline::VisionPipeline(std::shared_ptr<const ClassifierBank> bank, const PipelineParams& params)
    : bank_(std::move(bank)), state_(std::make_unique<State>()) {
    if (!bank_) throw std::invalid_argument("VisionPipeline: expected a classifier bank, got null");
    params.validate();
    state_->params = params;
    state_->params.front_end.normalizer = bank_->params().normalizer;
    state_->front_end = std::make_unique<FrontEnd>(state_->params.front_end);
    state_->tracker.set_params(params.tracker);
    state_->pending = state_->params;
}

VisionPipeline::~VisionPipeline() = default;

PipelineParams VisionPipeline::params() const {
    std::lock_guard<std::mutex> lock(params_mutex_);
    return state_->pending;
}

void VisionPipeline::set_params(const PipelineParams& params) {
    params.validate();
    PipelineParams p = params;
    p.front_end.normalizer = bank_->params().normalizer;
    FrontEnd check(p.front_end);  // cascade files exist: fail here, not in the stream
    std::lock_guard<std::mutex> lock(params_mutex_);
    state_->pending = p;
    state_->has_pending = true;
}

PipelineResult VisionPipeline::snapshot() const {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    return state_->last;
}

std::vector<cv::Rect> VisionPipeline::face_regions() const {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    std::vector<cv::Rect> out;
    for (const TrackReport& t : state_->last.tracks)
        if (t.seen) out.push_back(t.detection.box);
    return out;
}

PipelineResult VisionPipeline::process(const Frame& frame) {
    std::lock_guard<std::mutex> process_lock(process_mutex_);
    State& s = *state_;
    const auto t0 = std::chrono::steady_clock::now();
    {
        std::lock_guard<std::mutex> lock(params_mutex_);
        if (s.has_pending) {
            const bool restart = !same_accumulation(s.params.accumulator, s.pending.accumulator);
            s.params = s.pending;
            s.has_pending = false;
            s.front_end = std::make_unique<FrontEnd>(s.params.front_end);  // cascades checked in set_params
            s.tracker.set_params(s.params.tracker);
            if (restart)
                for (auto& [id, ev] : s.evidence) ev.accumulator = EvidenceAccumulator(s.params.accumulator);
        }
    }
    const PipelineParams& p = s.params;
    const UnknownRule rule = p.use_bank_rule ? bank_->unknown_rule() : p.unknown;

    PipelineResult r;
    r.frame = frame.index;
    r.timestamp = frame.timestamp;
    r.status = FrameStatus::Ok;
    r.image = frame.image;

    const FrontEndResult fe = s.front_end->process(frame.image);
    r.front_end_ms = ms_since(t0);
    r.faces_detected = int(fe.faces.size());

    const auto t1 = std::chrono::steady_clock::now();
    std::vector<BankScores> scores(fe.faces.size());
    std::vector<TrackerInput> inputs(fe.faces.size());
    for (std::size_t i = 0; i < fe.faces.size(); ++i) {
        scores[i] = bank_->scores(fe.faces[i].face.pixels);
        inputs[i].box = fe.faces[i].detection.box;
        if (p.use_appearance) inputs[i].appearance = appearance_signature(fe.faces[i].face.pixels);
    }
    r.scoring_ms = ms_since(t1);

    const TrackerUpdate up = s.tracker.update(inputs);
    for (int id : up.started) {
        s.evidence.emplace(id, State::TrackEvidence{EvidenceAccumulator(p.accumulator), false, {}, {}});
        PipelineEvent e;
        e.kind = PipelineEventKind::TrackStarted;
        e.frame = r.frame, e.timestamp = r.timestamp, e.track_id = id;
        r.events.push_back(e);
    }
    std::map<int, std::size_t> input_of;
    for (std::size_t i = 0; i < up.track_of.size(); ++i) {
        const int id = up.track_of[i];
        input_of[id] = i;
        State::TrackEvidence& ev = s.evidence.at(id);
        ev.accumulator.add(scores[i]);
        ev.detection = fe.faces[i].detection;
    }
    for (const Track& t : s.tracker.tracks()) {
        State::TrackEvidence& ev = s.evidence.at(t.id);
        TrackReport tr;
        tr.track_id = t.id;
        tr.detection = ev.detection;
        tr.detection.box = t.box;
        tr.missed = t.missed;
        tr.seen = t.missed == 0;
        tr.frames = ev.accumulator.frames();
        tr.decision = ev.accumulator.decide(rule);
        if (auto it = input_of.find(t.id); it != input_of.end())
            tr.frame_decision = decide(scores[it->second].names, scores[it->second].scores, rule);
        if (tr.frames >= p.min_frames) {
            const std::string name = tr.decision.known ? tr.decision.name : std::string();
            if (!ev.reported || name != ev.reported_name) {
                PipelineEvent e;
                e.kind = ev.reported ? PipelineEventKind::DecisionChanged : PipelineEventKind::DecisionMade;
                e.frame = r.frame, e.timestamp = r.timestamp, e.track_id = t.id;
                e.name = name;
                e.previous = ev.reported_name;
                e.score = tr.decision.score;
                e.frames = tr.frames;
                r.events.push_back(e);
                ev.reported = true;
                ev.reported_name = name;
            }
        }
        r.tracks.push_back(std::move(tr));
    }
    for (int id : up.ended) {
        PipelineEvent e;
        e.kind = PipelineEventKind::TrackLost;
        e.frame = r.frame, e.timestamp = r.timestamp, e.track_id = id;
        if (auto it = s.evidence.find(id); it != s.evidence.end()) {
            e.name = it->second.reported_name;
            e.frames = it->second.accumulator.frames();
            s.evidence.erase(it);
        }
        r.events.push_back(e);
    }
    r.total_ms = ms_since(t0);
    {
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        s.last = r;
    }
    return r;
}

PipelineResult VisionPipeline::note(FrameStatus status, const Frame& frame) {
    if (status == FrameStatus::Ok) throw std::invalid_argument("VisionPipeline::note: expected a non-Ok status, got ok");
    std::lock_guard<std::mutex> process_lock(process_mutex_);
    State& s = *state_;
    PipelineResult r;
    r.frame = frame.index;
    r.timestamp = frame.timestamp;
    r.status = status;
    PipelineEvent e;
    e.kind = status == FrameStatus::Skipped ? PipelineEventKind::FrameSkipped
             : status == FrameStatus::End   ? PipelineEventKind::StreamEnded
                                            : PipelineEventKind::SourceLost;
    e.frame = frame.index;
    e.timestamp = frame.timestamp;
    e.message = frame.message.empty() ? to_string(status) : frame.message;
    r.events.push_back(e);
    if (status != FrameStatus::Skipped) {
        for (const auto& [id, ev] : s.evidence) {
            PipelineEvent lost;
            lost.kind = PipelineEventKind::TrackLost;
            lost.frame = frame.index, lost.timestamp = frame.timestamp, lost.track_id = id;
            lost.name = ev.reported_name;
            lost.frames = ev.accumulator.frames();
            r.events.push_back(lost);
        }
        s.evidence.clear();
        s.tracker.reset();
    } else {
        std::lock_guard<std::mutex> lock(snapshot_mutex_);
        r.tracks = s.last.tracks;
    }
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    s.last = r;
    return r;
}

}  // namespace facesocial
