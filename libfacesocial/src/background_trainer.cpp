#include "facesocial/background_trainer.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace facesocial {

void BackgroundTrainerParams::validate() const {
    if (nice < 0 || nice > 19)
        throw std::invalid_argument("BackgroundTrainerParams: expected nice in [0, 19], got " + std::to_string(nice));
}

struct BackgroundTrainer::Impl {
    std::shared_ptr<ClassifierBank> bank;
    BackgroundTrainerParams params;
    mutable std::mutex mutex;
    std::condition_variable work, idle;
    std::deque<std::string> queue;
    bool busy = false, stopping = false;
    std::size_t done = 0;
    std::vector<std::string> failures;
    std::thread thread;

    void run() {
        // Lower this thread's priority only (on Linux, niceness is per thread).
        setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), params.nice);
        for (;;) {
            std::string name;
            {
                std::unique_lock<std::mutex> lock(mutex);
                work.wait(lock, [&] { return stopping || !queue.empty(); });
                if (stopping) break;
                name = queue.front();
                queue.pop_front();
                busy = true;
            }
            std::string failure;
            try {
                bank->train(name);
            } catch (const std::exception& e) {
                failure = name + ": " + e.what();
            }
            std::lock_guard<std::mutex> lock(mutex);
            busy = false;
            if (failure.empty())
                ++done;
            else
                failures.push_back(failure);
            idle.notify_all();
        }
        std::lock_guard<std::mutex> lock(mutex);
        busy = false;
        idle.notify_all();
    }
};

BackgroundTrainer::BackgroundTrainer(std::shared_ptr<ClassifierBank> bank, const BackgroundTrainerParams& params)
    : impl_(std::make_unique<Impl>()) {
    if (!bank) throw std::invalid_argument("BackgroundTrainer: expected a classifier bank, got null");
    params.validate();
    impl_->bank = std::move(bank);
    impl_->params = params;
    impl_->thread = std::thread([this] { impl_->run(); });
}

BackgroundTrainer::~BackgroundTrainer() {
    {
        std::lock_guard<std::mutex> lock(impl_->mutex);
        impl_->stopping = true;
        impl_->queue.clear();
    }
    impl_->work.notify_all();
    if (impl_->thread.joinable()) impl_->thread.join();
}

void BackgroundTrainer::request(const std::string& name) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    if (std::find(impl_->queue.begin(), impl_->queue.end(), name) == impl_->queue.end()) impl_->queue.push_back(name);
    impl_->work.notify_one();
}

void BackgroundTrainer::wait_idle() {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->idle.wait(lock, [&] { return (impl_->queue.empty() && !impl_->busy) || impl_->stopping; });
}

std::size_t BackgroundTrainer::pending() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->queue.size();
}

std::size_t BackgroundTrainer::trained() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->done;
}

std::vector<std::string> BackgroundTrainer::errors() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->failures;
}

}  // namespace facesocial
