// facesocial eval orl: the ORL protocol (canonical 1-5 / 6-10 split and seeded random 5/5
// splits), every classifier side by side.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <random>
#include <sstream>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

struct SplitResult {
    double accuracy = 0;
    double train_seconds = 0;
    double ms_per_face = 0;
};

/// Trains `kind` on train[p] and classifies every face of test[p].
SplitResult run_split(ClassifierKind kind, const std::vector<std::vector<cv::Mat>>& train,
                      const std::vector<std::vector<cv::Mat>>& test) {
    ClassifierParams params;
    params.kind = kind;
    auto classifier = FaceClassifier::create(params);
    auto t0 = Clock::now();
    classifier->train(train);
    SplitResult r;
    r.train_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    int correct = 0, total = 0;
    t0 = Clock::now();
    for (std::size_t p = 0; p < test.size(); ++p)
        for (const cv::Mat& face : test[p]) {
            const auto s = classifier->scores(face);
            correct += std::size_t(std::max_element(s.begin(), s.end()) - s.begin()) == p;
            ++total;
        }
    r.ms_per_face = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / std::max(total, 1);
    r.accuracy = double(correct) / std::max(total, 1);
    return r;
}


}  // namespace

int cmd_eval_orl(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--methods", "--splits"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const auto methods = parse_methods(args.get("--methods", "ehmm,eigen,fisher,lbph"));
    const int splits = args.get_int("--splits", 10);
    if (splits < 0) throw UsageError("--splits: expected >= 0");
    const bool json = args.flag("--json");

    // Faces are already cropped: normalise the whole image, without the elliptical mask.
    const FaceSet set = load_cropped_faces(root / "orl");
    const auto& faces = set.faces;
    for (std::size_t p = 0; p < faces.size(); ++p)
        if (faces[p].size() < 10) throw FileError((root / "orl" / set.names[p]).string(), "ORL person folder with fewer than 10 images");

    auto make_split = [&](const std::vector<std::vector<int>>& order, std::vector<std::vector<cv::Mat>>& train,
                          std::vector<std::vector<cv::Mat>>& test) {
        train.assign(faces.size(), {});
        test.assign(faces.size(), {});
        for (std::size_t p = 0; p < faces.size(); ++p)
            for (int i = 0; i < 10; ++i) (i < 5 ? train : test)[p].push_back(faces[p][order[p][i]]);
    };

    JsonObject result;
    result.add("dataset", "orl").add("people", int(faces.size())).add("splits", splits);
    std::vector<JsonObject> rows;
    if (!json)
        std::cout << std::left << std::setw(8) << "method" << std::right << std::setw(11) << "canonical" << std::setw(9)
                  << "mean" << std::setw(9) << "min" << std::setw(12) << "train s" << std::setw(12) << "ms/face"
                  << "\n";
    for (ClassifierKind kind : methods) {
        std::vector<std::vector<int>> order(faces.size(), std::vector<int>(10));
        for (auto& o : order) std::iota(o.begin(), o.end(), 0);
        std::vector<std::vector<cv::Mat>> train, test;
        make_split(order, train, test);
        const SplitResult canonical = run_split(kind, train, test);
        std::vector<double> acc;
        double train_s = canonical.train_seconds, ms = canonical.ms_per_face;
        for (int s = 0; s < splits; ++s) {
            // Split s depends on its seed alone: shuffle the identity order, not the previous split.
            std::mt19937 rng(1000 + s);
            for (auto& o : order) {
                std::iota(o.begin(), o.end(), 0);
                std::shuffle(o.begin(), o.end(), rng);
            }
            make_split(order, train, test);
            const SplitResult r = run_split(kind, train, test);
            acc.push_back(r.accuracy);
            train_s += r.train_seconds;
            ms += r.ms_per_face;
        }
        train_s /= (splits + 1);
        ms /= (splits + 1);
        const double mean = acc.empty() ? canonical.accuracy : std::accumulate(acc.begin(), acc.end(), 0.0) / acc.size();
        const double min = acc.empty() ? canonical.accuracy : *std::min_element(acc.begin(), acc.end());
        JsonObject row;
        row.add("method", to_string(kind)).add("canonical_accuracy", canonical.accuracy).add("mean_accuracy", mean);
        row.add("min_accuracy", min).add("split_accuracies", acc).add("train_seconds", train_s).add("ms_per_face", ms);
        rows.push_back(row);
        if (!json)
            std::cout << std::left << std::setw(8) << to_string(kind) << std::right << std::fixed << std::setprecision(3)
                      << std::setw(11) << canonical.accuracy << std::setw(9) << mean << std::setw(9) << min
                      << std::setw(12) << train_s << std::setw(12) << ms << std::endl;
    }
    result.add("methods", rows);
    if (json) std::cout << result.str() << "\n";
    return 0;
}

}  // namespace facesocial::cli
