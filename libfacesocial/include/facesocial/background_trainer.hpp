// Retrains people of a classifier bank in the background, on one low-priority thread, so a large
// training set (up to 400 samples, about 1 s per person) never stalls recognition: at most one
// core is used, at the lowest scheduling priority, and each new model swaps in atomically (the
// bank's own guarantee) while faces keep being scored.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "facesocial/classifier_bank.hpp"

namespace facesocial {

struct BackgroundTrainerParams {
    /// Niceness of the trainer thread (Linux; 0 = normal, 19 = lowest priority).
    int nice = 19;
    /// Throws std::invalid_argument when nice is outside [0, 19].
    void validate() const;
};

class BackgroundTrainer {
public:
    /// Starts the thread. std::invalid_argument for a null bank or invalid params.
    explicit BackgroundTrainer(std::shared_ptr<ClassifierBank> bank, const BackgroundTrainerParams& params = {});
    /// Finishes the person being trained, drops the rest of the queue and joins.
    ~BackgroundTrainer();
    BackgroundTrainer(const BackgroundTrainer&) = delete;
    BackgroundTrainer& operator=(const BackgroundTrainer&) = delete;

    /// Queues a person for retraining (once: a person already waiting is not queued again).
    void request(const std::string& name);
    /// Blocks until the queue is empty and nothing is being trained.
    void wait_idle();
    /// People waiting (not counting the one in training).
    std::size_t pending() const;
    /// People trained so far.
    std::size_t trained() const;
    /// Messages of trainings that failed (for example a person removed meanwhile).
    std::vector<std::string> errors() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace facesocial
