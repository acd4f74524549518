// Face tracks across video frames, so evidence is accumulated per face and not per frame
// (paper sections III.C.3 and V). Detections of a frame are associated with the existing tracks
// by an optimal assignment over a cost that combines overlap with the track's predicted box,
// centre distance and (optionally) appearance; tracks coast on their velocity through missed
// frames, so a face that is hidden for a moment (crossing behind another) or leaves and comes
// back soon keeps its track.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace facesocial {

/// Parameters of the tracker.
struct TrackerParams {
    /// A detection may join a track when its IoU with the track's predicted box is at least
    /// this, or when its centre lies within max_center_distance of the predicted centre.
    double min_iou = 0.1;
    /// Centre distance gate, as a share of the predicted box's width.
    double max_center_distance = 0.75;
    /// Weight of the appearance distance (1 - cosine similarity of appearance signatures, in
    /// [0, 2]) in the association cost; 0 = geometry only. Used when both sides have one.
    double appearance_weight = 1.0;
    /// Frames a track survives without a detection, coasting on its velocity. After that the
    /// track ends. At 5 fps, 10 frames = 2 s.
    int max_missed = 10;
    /// Smoothing of the velocity estimate: v = (1 - s) * measured + s * previous, in [0, 1).
    double velocity_smoothing = 0.5;
    /// Smoothing of the appearance signature (same form).
    double appearance_smoothing = 0.5;
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// One face of a frame offered to the tracker.
struct TrackerInput {
    cv::Rect box;
    /// Optional appearance signature (CV_32F, one row, any fixed length), e.g.
    /// appearance_signature() of the normalised face; empty = none.
    cv::Mat appearance;
};

/// The state of one track.
struct Track {
    int id = 0;              ///< unique within a tracker, increasing from 1
    cv::Rect box;            ///< last detected box, or the predicted one while coasting
    cv::Point2f velocity;    ///< pixels per frame of the box centre
    int age = 0;             ///< frames since the track started
    int hits = 0;            ///< frames with a detection
    int missed = 0;          ///< consecutive frames without a detection (0 = seen this frame)
    cv::Mat appearance;      ///< smoothed appearance signature (may be empty)
};

/// What one update did.
struct TrackerUpdate {
    std::vector<int> track_of;  ///< per input, in input order: the track id it was assigned to
    std::vector<int> started;   ///< ids of tracks started by this frame
    std::vector<int> ended;     ///< ids of tracks that ran out of max_missed this frame
};

/// Multi-face tracker. Not thread-safe: one tracker per video stream.
class FaceTracker {
public:
    /// Throws std::invalid_argument for invalid params.
    explicit FaceTracker(const TrackerParams& params = {});
    const TrackerParams& params() const { return params_; }
    /// Changes the parameters for the next frames (the tracks are kept).
    void set_params(const TrackerParams& params);

    /// Advances one frame. Every input is assigned to exactly one track (a new one when no
    /// live track is a plausible match); each track takes at most one input. Throws
    /// std::invalid_argument for an empty box or appearance signatures of different lengths.
    TrackerUpdate update(const std::vector<TrackerInput>& faces);

    /// The live tracks (seen this frame or coasting), by id.
    const std::vector<Track>& tracks() const { return tracks_; }
    /// Forgets every track (ids keep increasing).
    void reset();

private:
    TrackerParams params_;
    std::vector<Track> tracks_;
    int next_id_ = 1;
};

/// A small appearance signature of a normalised face: the face shrunk to 12x14 pixels,
/// zero-mean and unit-length (CV_32F, 1 x 168). Faces of different people are far apart in
/// cosine distance, two frames of one person close. Accepts any single-channel 8-bit or float
/// image; std::invalid_argument otherwise.
cv::Mat appearance_signature(const cv::Mat& face);

/// Minimum-cost assignment of rows to columns (Hungarian algorithm) of a rectangular cost
/// matrix (CV_64F). Entries >= `forbidden` may not be used. Returns, per row, the assigned
/// column or -1.
std::vector<int> assign_min_cost(const cv::Mat& cost, double forbidden);

}  // namespace facesocial
