#include "facesocial/pipeline_runner.hpp"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace facesocial {

void RunnerParams::validate() const {
    if (frame_queue < 1 || frame_queue > 10000)
        throw std::invalid_argument("RunnerParams: expected frame_queue in [1, 10000], got " + std::to_string(frame_queue));
    if (result_queue < 1 || result_queue > 100000)
        throw std::invalid_argument("RunnerParams: expected result_queue in [1, 100000], got " + std::to_string(result_queue));
    if (drop_frames < -1 || drop_frames > 1)
        throw std::invalid_argument("RunnerParams: expected drop_frames -1, 0 or 1, got " + std::to_string(drop_frames));
}

struct PipelineRunner::Impl {
    std::shared_ptr<VisionPipeline> pipeline;
    std::unique_ptr<VideoSource> source;
    RunnerParams params;
    bool drop = false;

    mutable std::mutex mutex;
    std::condition_variable frame_ready, frame_space, result_ready;
    struct Item {
        FrameStatus status;
        Frame frame;
    };
    std::deque<Item> frames;
    std::deque<PipelineResult> results;
    bool capture_done = false, process_done = false, stopping = false;
    RunnerStats stats;
    std::exception_ptr error;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::thread capture_thread, process_thread;

    void capture() {
        for (;;) {
            Item item;
            try {
                item.status = source->read(item.frame);
            } catch (...) {
                item.status = FrameStatus::Lost;
                item.frame.message = "the source failed while reading";
            }
            std::unique_lock<std::mutex> lock(mutex);
            if (stopping) break;
            if (item.status == FrameStatus::Ok) ++stats.frames_read;
            if (drop) {
                while (frames.size() >= params.frame_queue && item.status == FrameStatus::Ok) {
                    frames.pop_front();
                    ++stats.frames_dropped;
                }
            } else {
                frame_space.wait(lock, [&] { return frames.size() < params.frame_queue || stopping; });
                if (stopping) break;
            }
            const bool last = item.status == FrameStatus::End || item.status == FrameStatus::Lost;
            frames.push_back(std::move(item));
            frame_ready.notify_one();
            if (last) break;
        }
        std::lock_guard<std::mutex> lock(mutex);
        capture_done = true;
        frame_ready.notify_all();
    }

    void process() {
        for (;;) {
            Item item;
            {
                std::unique_lock<std::mutex> lock(mutex);
                frame_ready.wait(lock, [&] { return !frames.empty() || capture_done || stopping; });
                if (stopping || frames.empty()) break;
                item = std::move(frames.front());
                frames.pop_front();
                frame_space.notify_one();
            }
            PipelineResult r;
            try {
                r = item.status == FrameStatus::Ok ? pipeline->process(item.frame) : pipeline->note(item.status, item.frame);
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                error = std::current_exception();
                stopping = true;
                frame_space.notify_all();
                break;
            }
            const bool last = item.status == FrameStatus::End || item.status == FrameStatus::Lost;
            std::lock_guard<std::mutex> lock(mutex);
            if (item.status == FrameStatus::Ok) ++stats.frames_processed;
            results.push_back(std::move(r));
            while (results.size() > params.result_queue) {
                results.pop_front();
                ++stats.results_dropped;
            }
            result_ready.notify_all();
            if (last) break;
        }
        std::lock_guard<std::mutex> lock(mutex);
        process_done = true;
        result_ready.notify_all();
    }
};

PipelineRunner::PipelineRunner(std::shared_ptr<VisionPipeline> pipeline, std::unique_ptr<VideoSource> source,
                               const RunnerParams& params)
    : impl_(std::make_unique<Impl>()) {
    if (!pipeline) throw std::invalid_argument("PipelineRunner: expected a pipeline, got null");
    if (!source) throw std::invalid_argument("PipelineRunner: expected a video source, got null");
    params.validate();
    impl_->pipeline = std::move(pipeline);
    impl_->source = std::move(source);
    impl_->params = params;
    impl_->drop = params.drop_frames == 1 || (params.drop_frames == -1 && impl_->source->is_live());
    impl_->process_thread = std::thread([this] { impl_->process(); });
    impl_->capture_thread = std::thread([this] { impl_->capture(); });
}

PipelineRunner::~PipelineRunner() {
    stop();
    if (impl_->capture_thread.joinable()) impl_->capture_thread.join();
    if (impl_->process_thread.joinable()) impl_->process_thread.join();
}

void PipelineRunner::stop() {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stopping = true;
    impl_->frame_ready.notify_all();
    impl_->frame_space.notify_all();
    impl_->result_ready.notify_all();
}

bool PipelineRunner::next(PipelineResult& result, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->result_ready.wait_for(lock, timeout, [&] { return !impl_->results.empty() || impl_->process_done; });
    if (impl_->results.empty()) return false;
    result = std::move(impl_->results.front());
    impl_->results.pop_front();
    return true;
}

bool PipelineRunner::finished() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->process_done && impl_->results.empty();
}

RunnerStats PipelineRunner::stats() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    RunnerStats s = impl_->stats;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - impl_->start).count();
    s.processing_fps = seconds > 0 ? double(s.frames_processed) / seconds : 0;
    return s;
}

std::exception_ptr PipelineRunner::error() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->error;
}

}  // namespace facesocial
