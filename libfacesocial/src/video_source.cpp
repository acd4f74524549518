#include "facesocial/video_source.hpp"

#include <chrono>
#include <filesystem>

#include <opencv2/videoio.hpp>

#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial {

std::string to_string(FrameStatus status) {
    switch (status) {
    case FrameStatus::Ok: return "ok";
    case FrameStatus::Skipped: return "skipped";
    case FrameStatus::End: return "end";
    case FrameStatus::Lost: return "lost";
    }
    return "?";
}

namespace {

namespace fs = std::filesystem;

bool is_camera_index(const std::string& s) {
    return !s.empty() && s.size() <= 3 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// cv::VideoCapture over a camera, a file or a URL.
class CaptureSource : public VideoSource {
public:
    CaptureSource(const std::string& spec, bool camera, bool url) : spec_(spec), live_(camera || url) {
        if (camera) {
            cap_.open(std::stoi(spec));
            if (!cap_.isOpened()) throw FileError("camera " + spec, "no such camera, or it cannot be opened");
            description_ = "camera " + spec;
        } else {
            if (!url) {
                std::error_code ec;
                if (!fs::exists(spec, ec)) throw FileError(spec, "no such video file");
                if (fs::is_directory(spec, ec)) throw FileError(spec, "is a folder without frame images");
            }
            cap_.open(spec);
            if (!cap_.isOpened()) throw FileError(spec, url ? "the stream cannot be opened" : "not a video OpenCV can decode");
            description_ = (url ? "stream " : "file ") + spec;
        }
        fps_ = cap_.get(cv::CAP_PROP_FPS);
        if (!(fps_ > 0 && fps_ < 1000)) fps_ = 0;
        const double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
        count_ = live_ || !(n > 0) ? -1 : static_cast<long long>(n);
        // A file whose first frame cannot be decoded is not a video (OpenCV opens some garbage).
        if (!live_) {
            Frame first;
            if (read(first) != FrameStatus::Ok) throw FileError(spec, "not a video OpenCV can decode (no frame could be read)");
            pending_ = std::move(first);
            has_pending_ = true;
        }
        start_ = std::chrono::steady_clock::now();
    }

    FrameStatus read(Frame& frame) override {
        if (has_pending_) {
            frame = std::move(pending_);
            has_pending_ = false;
            return FrameStatus::Ok;
        }
        if (ended_) return live_ ? FrameStatus::Lost : FrameStatus::End;
        cv::Mat img;
        bool ok = false;
        try {
            ok = cap_.read(img);
        } catch (const cv::Exception& e) {
            frame.message = e.what();
            ok = false;
        }
        if (!ok || img.empty()) {
            ended_ = true;
            frame.image.release();
            frame.index = next_;
            frame.timestamp = !live_ && fps_ > 0 ? double(next_) / fps_
                                                 : std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
            if (live_) {
                frame.message = description_ + " stopped delivering frames";
                return FrameStatus::Lost;
            }
            frame.message = "end of " + description_ + " after " + std::to_string(next_) + " frames";
            if (count_ > 0 && next_ < count_) frame.message += " (the file announced " + std::to_string(count_) + ")";
            return FrameStatus::End;
        }
        frame.image = img;
        frame.index = next_++;
        frame.timestamp = !live_ && fps_ > 0 ? double(frame.index) / fps_
                                             : std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        frame.message.clear();
        return FrameStatus::Ok;
    }

    bool is_live() const override { return live_; }
    long long frame_count() const override { return count_; }
    double fps() const override { return fps_; }
    std::string description() const override { return description_; }

private:
    std::string spec_;
    bool live_;
    cv::VideoCapture cap_;
    std::string description_;
    double fps_ = 0;
    long long count_ = -1;
    long long next_ = 0;
    bool ended_ = false;
    Frame pending_;
    bool has_pending_ = false;
    std::chrono::steady_clock::time_point start_;
};

/// Frame images of a folder, in natural order, at a nominal rate.
class FolderSource : public VideoSource {
public:
    explicit FolderSource(const std::string& folder) : folder_(folder), files_(list_images(folder)) {
        if (files_.empty()) throw FileError(folder, "folder holds no frame images");
    }
    FrameStatus read(Frame& frame) override {
        if (next_ >= files_.size()) {
            frame.image.release();
            frame.index = static_cast<long long>(files_.size());
            frame.timestamp = double(files_.size()) / fps();
            frame.message = "end of " + description();
            return FrameStatus::End;
        }
        const std::size_t i = next_++;
        frame.index = static_cast<long long>(i);
        frame.timestamp = double(i) / fps();
        try {
            frame.image = load_image(files_[i], ImageColor::Any);
            frame.message.clear();
            return FrameStatus::Ok;
        } catch (const FileError& e) {
            frame.image.release();
            frame.message = e.what();
            return FrameStatus::Skipped;
        }
    }
    bool is_live() const override { return false; }
    long long frame_count() const override { return static_cast<long long>(files_.size()); }
    double fps() const override { return 5.0; }  // the paper's rate; folders carry no timing
    std::string description() const override {
        return "folder " + folder_ + " (" + std::to_string(files_.size()) + " images)";
    }

private:
    std::string folder_;
    std::vector<fs::path> files_;
    std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<VideoSource> VideoSource::open(const std::string& spec) {
    if (spec.empty()) throw FileError("<empty>", "no video source given");
    if (is_camera_index(spec)) return std::make_unique<CaptureSource>(spec, true, false);
    if (spec.find("://") != std::string::npos) return std::make_unique<CaptureSource>(spec, false, true);
    std::error_code ec;
    if (fs::is_directory(spec, ec)) return std::make_unique<FolderSource>(spec);
    return std::make_unique<CaptureSource>(spec, false, false);
}

}  // namespace facesocial
