// Where frames come from: a camera (by index), a video file or stream URL (cv::VideoCapture), or
// a folder of frame images. A camera that disappears, a corrupt frame or the end of the stream
// is a status of read(), never a crash or a hang.
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

namespace facesocial {

/// What read() got.
enum class FrameStatus {
    Ok,       ///< a frame
    Skipped,  ///< this frame could not be decoded (corrupt image in a folder); the next may be fine
    End,      ///< end of a file or folder; no more frames
    Lost,     ///< a live source stopped delivering (camera unplugged, stream dropped)
};

/// "ok", "skipped", "end", "lost".
std::string to_string(FrameStatus status);

/// One frame and where it is in the stream.
struct Frame {
    cv::Mat image;           ///< 8-bit BGR (or grey for grey frame images)
    long long index = -1;    ///< 0-based position in the stream
    double timestamp = 0;    ///< seconds since the start (file: from its frame rate; live: wall clock)
    std::string message;     ///< why, when the status is not Ok
};

/// A stream of frames. Not thread-safe: read from one thread.
class VideoSource {
public:
    virtual ~VideoSource() = default;
    /// Reads the next frame into `frame` and says what happened.
    virtual FrameStatus read(Frame& frame) = 0;
    /// True for cameras and network streams (frames may be dropped to stay live).
    virtual bool is_live() const = 0;
    /// Frames in the stream when known (files, folders), otherwise -1.
    virtual long long frame_count() const = 0;
    /// Frames per second of the stream when known, otherwise 0.
    virtual double fps() const = 0;
    /// What was opened ("camera 0", "file clip.mp4", "folder frames/ (120 images)").
    virtual std::string description() const = 0;

    /// Opens `spec`: a non-negative integer is a camera index; an existing folder is read as
    /// frame images in natural order; anything with "://" is a stream URL; otherwise a video
    /// file. Throws FileError when it cannot be opened (missing file, no such camera, not a
    /// video, an empty folder), saying which.
    static std::unique_ptr<VideoSource> open(const std::string& spec);
};

}  // namespace facesocial
