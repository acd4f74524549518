// The live vision pipeline (paper sections III.C and V): frame -> detect (frontal, optionally
// profile) -> skin filter -> normalise -> score against the classifier bank -> face tracks ->
// accumulated evidence per track -> decision. It keeps the latest snapshot (tracks, boxes,
// decisions) for anyone who asks, reports track events, and its parameters can be read and
// changed while it runs (the paper's "set / query operational parameters").
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/evidence_accumulator.hpp"
#include "facesocial/face_tracker.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/video_source.hpp"

namespace facesocial {

/// Everything that shapes the pipeline; may be changed between frames.
struct PipelineParams {
    /// Detection, skin filter and normalisation. Defaults: the fast frontal and profile presets
    /// (CascadeDetectorParams::fast_frontal() / fast_profile(), made for live 640x480 video),
    /// profile off, skin filter on. The normaliser is always the bank's own (its params are replaced).
    FrontEndParams front_end = default_front_end();
    TrackerParams tracker;           ///< association of faces across frames
    AccumulatorParams accumulator;   ///< evidence per track (paper: 25-frame moving average)
    /// Use the appearance of the normalised face in the association cost.
    bool use_appearance = true;
    /// Apply the bank's own unknown rule (read at every frame, so changes to it take effect).
    bool use_bank_rule = true;
    UnknownRule unknown;             ///< used when use_bank_rule is false
    /// Frames of evidence a track needs before its decision is reported as an event.
    int min_frames = 3;

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
    /// The default front end of the pipeline (see front_end).
    static FrontEndParams default_front_end();
};

/// One face track as the pipeline sees it after a frame.
struct TrackReport {
    int track_id = 0;
    Detection detection;      ///< last detection (box predicted while coasting)
    bool seen = false;        ///< detected in this frame
    int missed = 0;           ///< consecutive frames without a detection
    int frames = 0;           ///< frames of evidence in the accumulator
    Decision decision;        ///< from the accumulated scores
    Decision frame_decision;  ///< from this frame's scores alone (empty when not seen)
};

/// Something worth telling the rest of the robot.
enum class PipelineEventKind {
    TrackStarted,     ///< a new face appeared
    DecisionMade,     ///< a track's accumulated decision is reported for the first time
    DecisionChanged,  ///< ... and when its name (or unknown) changes
    TrackLost,        ///< a track ended (face gone for longer than the tracker's max_missed)
    FrameSkipped,     ///< a frame could not be decoded
    StreamEnded,      ///< end of file or folder
    SourceLost,       ///< a camera or stream stopped delivering
};

/// "track_started", "decision_made", "decision_changed", "track_lost", "frame_skipped",
/// "stream_ended", "source_lost".
std::string to_string(PipelineEventKind kind);

struct PipelineEvent {
    PipelineEventKind kind = PipelineEventKind::TrackStarted;
    long long frame = -1;      ///< frame index
    double timestamp = 0;      ///< seconds
    int track_id = 0;          ///< 0 for stream events
    std::string name;          ///< decision: the name, "" = unknown
    std::string previous;      ///< DecisionChanged: the previous name ("" = unknown)
    double score = 0;          ///< decision: accumulated best score
    int frames = 0;            ///< decision: frames of evidence
    std::string message;       ///< stream events: what happened
};

/// The outcome of one frame (or of a stream status).
struct PipelineResult {
    long long frame = -1;
    double timestamp = 0;
    FrameStatus status = FrameStatus::Ok;
    cv::Mat image;                     ///< the frame (shares its pixels; empty for a status)
    std::vector<TrackReport> tracks;   ///< live tracks, by id
    std::vector<PipelineEvent> events;
    int faces_detected = 0;            ///< faces that passed the front end
    double front_end_ms = 0;           ///< detection + skin filter + normalisation
    double scoring_ms = 0;             ///< bank scoring of every face
    double total_ms = 0;
};

/// Runs the per-frame chain for one video stream.
///
/// process() is for one stream at a time (calls are serialised). params(), set_params(),
/// snapshot() and face_regions() may be called from any thread at any time.
class VisionPipeline {
public:
    /// Throws std::invalid_argument for a null bank or invalid params, FileError for a missing
    /// cascade. The bank may be trained and retrained while the pipeline runs.
    VisionPipeline(std::shared_ptr<const ClassifierBank> bank, const PipelineParams& params = {});
    ~VisionPipeline();

    /// Processes one frame (8-bit grey or BGR; std::invalid_argument otherwise).
    PipelineResult process(const Frame& frame);
    /// Turns a non-Ok read status into its event. End and Lost also end every track
    /// (TrackLost events) and reset the tracker.
    PipelineResult note(FrameStatus status, const Frame& frame);

    PipelineParams params() const;
    /// Validates and applies from the next frame on. A changed accumulator kind or window
    /// restarts the evidence of the current tracks.
    void set_params(const PipelineParams& params);

    /// The result of the latest frame.
    PipelineResult snapshot() const;
    /// The face boxes of the latest frame (tracks seen in it).
    std::vector<cv::Rect> face_regions() const;

    const ClassifierBank& bank() const { return *bank_; }

private:
    struct State;
    std::shared_ptr<const ClassifierBank> bank_;
    std::unique_ptr<State> state_;
    mutable std::mutex params_mutex_, snapshot_mutex_;
    std::mutex process_mutex_;
};

}  // namespace facesocial
