// Runs a VisionPipeline on a VideoSource in the background: one thread captures, one processes,
// so decoding the next frame overlaps with recognising the current one. Results go to a bounded
// queue that drops its oldest entry when the consumer falls behind: the pipeline never waits for
// a slow consumer. Live sources (cameras, streams) also drop frames that capture faster than
// processing; files and folders are processed frame by frame.
#pragma once

#include <chrono>
#include <memory>

#include "facesocial/video_source.hpp"
#include "facesocial/vision_pipeline.hpp"

namespace facesocial {

struct RunnerParams {
    std::size_t frame_queue = 2;    ///< frames waiting for processing, >= 1
    std::size_t result_queue = 8;   ///< results waiting for the consumer, >= 1; the oldest is dropped
    /// Drop the oldest waiting frame when processing falls behind. -1 = for live sources only,
    /// 0 = never, 1 = always.
    int drop_frames = -1;
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

struct RunnerStats {
    long long frames_read = 0;        ///< frames the source delivered
    long long frames_processed = 0;
    long long frames_dropped = 0;     ///< live sources: frames skipped to stay current
    long long results_dropped = 0;    ///< results the consumer did not take in time
    double processing_fps = 0;        ///< processed frames per second of wall time so far
};

class PipelineRunner {
public:
    /// Starts the threads at once. Throws std::invalid_argument for null arguments or invalid
    /// params.
    PipelineRunner(std::shared_ptr<VisionPipeline> pipeline, std::unique_ptr<VideoSource> source,
                   const RunnerParams& params = {});
    /// Stops and joins the threads.
    ~PipelineRunner();
    PipelineRunner(const PipelineRunner&) = delete;
    PipelineRunner& operator=(const PipelineRunner&) = delete;

    /// Waits up to `timeout` for the next result. False on timeout, or when the run is over
    /// and every result has been taken (see finished()).
    bool next(PipelineResult& result, std::chrono::milliseconds timeout = std::chrono::milliseconds(1000));
    /// True once the source ended or was lost (or stop() was called) and every result was taken.
    bool finished() const;
    /// Asks the threads to stop; next() then returns what is queued and false after it.
    void stop();
    RunnerStats stats() const;
    /// An exception thrown inside the processing thread (for example a corrupt frame size the
    /// front end refuses) ends the run; it is rethrown here, or nullptr when none.
    std::exception_ptr error() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace facesocial
