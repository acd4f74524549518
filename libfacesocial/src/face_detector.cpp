#include "facesocial/face_detector.hpp"

#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "checks.hpp"
#include "facesocial/error.hpp"
#include "parallel.hpp"

namespace facesocial {

namespace fs = std::filesystem;

namespace {

// Confidence = n / (n + kHalfConfidenceWindows) for a detection supported by n raw windows:
// monotone, in (0, 1), 0.5 at 4 windows.
constexpr double kHalfConfidenceWindows = 4.0;

// OpenCV's haarcascade_profileface.xml was trained on faces whose nose points to the image's
// left edge; on the mirrored image it finds faces pointing right.
constexpr FacePose kDirectProfilePose = FacePose::ProfileLeft;
constexpr FacePose kMirroredProfilePose = FacePose::ProfileRight;

cv::Mat to_grey(const cv::Mat& image, bool equalize) {
    cv::Mat grey;
    if (image.channels() == 3)
        cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    else
        grey = image;
    if (equalize) {
        cv::Mat eq;
        cv::equalizeHist(grey, eq);
        return eq;
    }
    return grey;
}

class CascadeDetector final : public FaceDetector {
public:
    explicit CascadeDetector(const CascadeDetectorParams& params) : params_(params) {
        params_.validate();
        file_ = find_cascade(params_.cascade_file.empty() ? fs::path(default_cascade_file(params_.kind))
                                                          : params_.cascade_file);
        bool loaded = false;
        try {
            loaded = cascade_.load(file_.string());
        } catch (const cv::Exception& e) {
            throw FileError(file_.string(), std::string("is not a readable cascade: ") + e.what());
        }
        if (!loaded || cascade_.empty())
            throw FileError(file_.string(), "is not a readable OpenCV cascade classifier XML file");
        window_ = cascade_.getOriginalWindowSize();
    }

    std::vector<Detection> detect(const cv::Mat& image) const override {
        if (image.type() == CV_8UC4)
            detail::fail("FaceDetector::detect", "an 8-bit 1- or 3-channel image (convert BGRA to BGR first)",
                         "CV_8UC4");
        detail::require_8bit_grey_or_bgr(image, "FaceDetector::detect");
        const int min_side = std::max(params_.min_face_size, std::max(window_.width, window_.height));
        if (image.cols < min_side || image.rows < min_side)
            detail::fail("FaceDetector::detect",
                         "an image of at least " + std::to_string(min_side) + "x" + std::to_string(min_side) +
                             " pixels (the smallest face searched)",
                         detail::size_string(image.size()));

        double scale = 1.0;
        cv::Mat work = image;
        if (params_.max_working_width > 0 && image.cols > params_.max_working_width) {
            scale = double(params_.max_working_width) / image.cols;
            cv::resize(image, work, cv::Size(), scale, scale, cv::INTER_AREA);
        }
        const cv::Mat grey = to_grey(work, params_.equalize);
        const int min_size = std::max(1, int(params_.min_face_size * scale + 0.5));
        const int max_size = params_.max_face_size > 0 ? int(params_.max_face_size * scale + 0.5) : 0;

        std::vector<Detection> found = run(grey, min_size, max_size,
                                           params_.kind == CascadeKind::Frontal ? FacePose::Frontal
                                                                                : kDirectProfilePose);
        if (params_.kind == CascadeKind::Profile && params_.mirror_profile) {
            cv::Mat mirrored;
            cv::flip(grey, mirrored, 1);
            for (Detection d : run(mirrored, min_size, max_size, kMirroredProfilePose)) {
                d.box.x = grey.cols - d.box.x - d.box.width;
                found.push_back(d);
            }
            found = merge_detections(std::move(found), params_.merge);
        }
        const cv::Rect bounds(0, 0, image.cols, image.rows);
        for (Detection& d : found) {
            if (scale != 1.0) {
                d.box = cv::Rect(cvRound(d.box.x / scale), cvRound(d.box.y / scale), cvRound(d.box.width / scale),
                                 cvRound(d.box.height / scale));
            }
            d.box &= bounds;
        }
        std::erase_if(found, [](const Detection& d) { return d.box.area() == 0; });
        std::stable_sort(found.begin(), found.end(),
                         [](const Detection& a, const Detection& b) { return a.confidence > b.confidence; });
        return found;
    }

    std::string name() const override {
        return std::string("cascade ") + (params_.kind == CascadeKind::Frontal ? "frontal " : "profile ") +
               file_.filename().string();
    }

private:
    std::vector<Detection> run(const cv::Mat& grey, int min_size, int max_size, FacePose pose) const {
        std::vector<cv::Rect> boxes;
        std::vector<int> windows;
        {
            // cv::CascadeClassifier keeps scratch state: one call at a time per object.
            std::lock_guard<std::mutex> lock(mutex_);
            cascade_.detectMultiScale(grey, boxes, windows, params_.scale_factor, params_.min_neighbors, 0,
                                      cv::Size(min_size, min_size),
                                      max_size > 0 ? cv::Size(max_size, max_size) : cv::Size());
        }
        std::vector<Detection> out;
        out.reserve(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const double n = i < windows.size() ? windows[i] : params_.min_neighbors;
            out.push_back({boxes[i], pose, float(n / (n + kHalfConfidenceWindows))});
        }
        return out;
    }

    CascadeDetectorParams params_;
    fs::path file_;
    cv::Size window_;
    mutable cv::CascadeClassifier cascade_;
    mutable std::mutex mutex_;
};

class CombinedDetector final : public FaceDetector {
public:
    CombinedDetector(std::vector<std::shared_ptr<FaceDetector>> parts, const MergeParams& merge)
        : parts_(std::move(parts)), merge_(merge) {
        merge_.validate();
        if (parts_.empty()) detail::fail("FaceDetector::combine", "at least one detector", "none");
        for (const auto& p : parts_)
            if (!p) detail::fail("FaceDetector::combine", "non-null detectors", "a null pointer");
    }

    std::vector<Detection> detect(const cv::Mat& image) const override {
        std::vector<std::vector<Detection>> per_part(parts_.size());
        detail::parallel_for(parts_.size(), [&](std::size_t i) { per_part[i] = parts_[i]->detect(image); });
        std::vector<Detection> all;
        for (auto& v : per_part) all.insert(all.end(), v.begin(), v.end());
        return merge_detections(std::move(all), merge_);
    }

    std::string name() const override {
        std::string n = "combined(";
        for (std::size_t i = 0; i < parts_.size(); ++i) n += (i ? ", " : "") + parts_[i]->name();
        return n + ")";
    }

private:
    std::vector<std::shared_ptr<FaceDetector>> parts_;
    MergeParams merge_;
};

}  // namespace

void CascadeDetectorParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, const std::string& got) {
        throw std::invalid_argument("CascadeDetectorParams: expected " + field + " " + expected + ", got " + got);
    };
    if (!(scale_factor > 1.0 && scale_factor < 4.0)) bad("scale_factor", "in (1, 4)", std::to_string(scale_factor));
    if (min_neighbors < 1) bad("min_neighbors", ">= 1", std::to_string(min_neighbors));
    if (min_face_size < 1) bad("min_face_size", ">= 1", std::to_string(min_face_size));
    if (max_face_size != 0 && max_face_size < min_face_size)
        bad("max_face_size", "0 or >= min_face_size (" + std::to_string(min_face_size) + ")",
            std::to_string(max_face_size));
    if (max_working_width < 0) bad("max_working_width", ">= 0", std::to_string(max_working_width));
    merge.validate();
}

CascadeDetectorParams CascadeDetectorParams::fast_frontal() {
    CascadeDetectorParams p;
    p.cascade_file = "lbpcascade_frontalface.xml";
    p.min_face_size = 32;
    p.max_working_width = 320;
    return p;
}

CascadeDetectorParams CascadeDetectorParams::fast_profile() {
    CascadeDetectorParams p = profile_cascade_params();
    p.cascade_file = "lbpcascade_profileface.xml";
    p.min_face_size = 32;
    p.max_working_width = 320;
    return p;
}

std::unique_ptr<FaceDetector> FaceDetector::create(const CascadeDetectorParams& params) {
    return std::make_unique<CascadeDetector>(params);
}

std::unique_ptr<FaceDetector> FaceDetector::combine(std::vector<std::shared_ptr<FaceDetector>> parts,
                                                    const MergeParams& merge) {
    return std::make_unique<CombinedDetector>(std::move(parts), merge);
}

std::unique_ptr<FaceDetector> create_default_detector(bool with_profile) {
    std::vector<std::shared_ptr<FaceDetector>> parts;
    parts.push_back(FaceDetector::create(CascadeDetectorParams{}));
    if (with_profile) {
        CascadeDetectorParams profile;
        profile.kind = CascadeKind::Profile;
        parts.push_back(FaceDetector::create(profile));
    }
    return FaceDetector::combine(std::move(parts));
}

std::string default_cascade_file(CascadeKind kind) {
    return kind == CascadeKind::Frontal ? "haarcascade_frontalface_alt2.xml" : "haarcascade_profileface.xml";
}

fs::path find_cascade(const fs::path& file) {
    std::error_code ec;
    if (file.empty()) throw std::invalid_argument("find_cascade: expected a cascade file name, got an empty path");
    if (fs::is_regular_file(file, ec)) return file;
    std::vector<fs::path> places;
    if (file.has_parent_path()) {
        throw FileError(file.string(), "cascade file not found");
    }
    if (const char* dir = std::getenv("FACESOCIAL_CASCADE_DIR"); dir && *dir) places.emplace_back(dir);
    for (const char* prefix : {"/usr/share/opencv4", "/usr/local/share/opencv4"})
        for (const char* sub : {"haarcascades", "lbpcascades"}) places.push_back(fs::path(prefix) / sub);
    std::string searched;
    for (const auto& dir : places) {
        if (fs::is_regular_file(dir / file, ec)) return dir / file;
        searched += (searched.empty() ? "" : ", ") + dir.string();
    }
    throw FileError(file.string(), "cascade file not found in " + searched +
                                       " (install Debian's opencv-data or set FACESOCIAL_CASCADE_DIR)");
}

}  // namespace facesocial
