// Face detectors: the pluggable interface, Viola-Jones cascades (frontal and profile) and a
// combination of several detectors run on one frame with their detections merged.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/detection.hpp"

namespace facesocial {

/// Which face model a cascade detector runs.
enum class CascadeKind {
    Frontal,  ///< frontal faces; detections have pose Frontal
    Profile,  ///< profile faces; the cascade sees one side, so it also runs on the mirrored image
};

/// Parameters of a Viola-Jones cascade detector (OpenCV objdetect).
struct CascadeDetectorParams {
    CascadeKind kind = CascadeKind::Frontal;  ///< frontal or profile model
    /// Cascade XML file. Empty: default_cascade_file(kind) looked up by find_cascade().
    std::filesystem::path cascade_file;
    double scale_factor = 1.1;  ///< step between pyramid scales, > 1
    int min_neighbors = 3;      ///< raw windows that must agree for a detection, >= 1
    int min_face_size = 24;     ///< smallest face side searched, in pixels of the input image
    int max_face_size = 0;      ///< largest face side searched; 0 = no limit
    /// Frames wider than this are downscaled before detection (boxes are mapped back);
    /// 0 = always detect at full resolution. Trades small-face recall for speed.
    int max_working_width = 0;
    /// Histogram-equalise the grey frame first. Off by default: on dlib_faces it adds false
    /// positives and loses two faces with the default cascade.
    bool equalize = false;
    /// Profile kind only: also run on the mirrored image to find the other side.
    bool mirror_profile = true;
    MergeParams merge;  ///< merging of the direct and mirrored profile detections

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;

    /// Preset for live 640x480 video on one core (see docs/BENCHMARKS.md): the LBP frontal
    /// cascade on the frame downscaled to 320 pixels wide, faces from 32 pixels. About 10x
    /// faster than the defaults; loses the smallest faces.
    static CascadeDetectorParams fast_frontal();
    /// The same for the profile model: the LBP profile cascade (both sides) on the frame
    /// downscaled to 320 pixels wide, faces from 32 pixels.
    static CascadeDetectorParams fast_profile();
};

/// Default params of a profile cascade detector.
inline CascadeDetectorParams profile_cascade_params() {
    CascadeDetectorParams p;
    p.kind = CascadeKind::Profile;
    return p;
}

/// Finds and detects faces in 8-bit grey or BGR images.
///
/// detect() requires an 8-bit image with 1 or 3 channels (or 4: BGRA is refused with a clear
/// error) at least as large as the smallest face searched; otherwise std::invalid_argument.
/// Implementations are safe to call from several threads.
class FaceDetector {
public:
    virtual ~FaceDetector() = default;

    /// Detections in image coordinates, each box inside the image, sorted by confidence.
    virtual std::vector<Detection> detect(const cv::Mat& image) const = 0;

    /// Short human-readable description ("cascade frontal haarcascade_frontalface_default.xml").
    virtual std::string name() const = 0;

    /// A cascade detector. Throws FileError when the cascade file is missing or unreadable and
    /// std::invalid_argument when the params are invalid.
    static std::unique_ptr<FaceDetector> create(const CascadeDetectorParams& params = {});

    /// Runs every part on the same frame (in parallel) and merges overlapping detections, as
    /// the paper runs a frontal and a profile detector side by side.
    static std::unique_ptr<FaceDetector> combine(std::vector<std::shared_ptr<FaceDetector>> parts,
                                                 const MergeParams& merge = {});
};

/// The frontal (and, when `with_profile`, profile) cascade detectors with default params,
/// combined. The usual front end.
std::unique_ptr<FaceDetector> create_default_detector(bool with_profile);

/// File name of the cascade used by default for `kind` ("haarcascade_frontalface_alt2.xml"
/// or "haarcascade_profileface.xml").
std::string default_cascade_file(CascadeKind kind);

/// Resolves a cascade file: an existing path is returned as is; a bare file name is searched in
/// $FACESOCIAL_CASCADE_DIR, then /usr/share/opencv4/{haarcascades,lbpcascades} and
/// /usr/local/share/opencv4/{haarcascades,lbpcascades}. Throws FileError listing the places
/// searched when nothing is found.
std::filesystem::path find_cascade(const std::filesystem::path& file);

}  // namespace facesocial
