// facesocial eval identify (any two identity folders) and eval unknown (open-set ORL), both
// through the classifier bank.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "face_input.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/open_set_eval.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct LabelledFaces {
    std::vector<std::string> names;
    std::vector<std::vector<cv::Mat>> faces;
    int images = 0;
    int without_face = 0;
};

/// One normalised face per image (the largest detected one with a front end).
LabelledFaces load_faces(const fs::path& folder, const ClassifierBank& proto, const FrontEnd* front_end) {
    LabelledFaces out;
    for (const PersonImages& p : load_identity_folders(folder)) {
        out.names.push_back(p.name);
        out.faces.emplace_back();
        for (const fs::path& f : p.images) {
            ++out.images;
            const auto found = faces_of(load_image(f, ImageColor::Any), proto, front_end);
            if (found.empty())
                ++out.without_face;
            else
                out.faces.back().push_back(found.front().face);
        }
    }
    return out;
}

}  // namespace

int cmd_eval_identify(const std::vector<std::string>& argv) {
    const Args args(argv, {"--train", "--test", "--methods"}, {"--detect", "--json"});
    if (!args.has("--train") || !args.has("--test")) throw UsageError("eval identify: expected --train DIR and --test DIR");
    const auto methods = parse_methods(args.get("--methods", "ehmm,eigen,fisher,lbph"));
    const bool json = args.flag("--json");
    const auto front_end = make_front_end(args.flag("--detect"));
    ClassifierBankParams base;
    base.normalizer = front_end ? NormalizerParams{} : NormalizerParams::cropped();
    const ClassifierBank proto(base);
    const LabelledFaces train = load_faces(args.get("--train"), proto, front_end.get());
    const LabelledFaces test = load_faces(args.get("--test"), proto, front_end.get());

    JsonObject result;
    result.add("train", args.get("--train")).add("test", args.get("--test")).add("detect", bool(front_end));
    result.add("train_images", train.images).add("train_without_face", train.without_face);
    result.add("test_images", test.images).add("test_without_face", test.without_face);
    if (!json)
        std::cout << "train: " << train.names.size() << " people, " << train.images << " images (" << train.without_face
                  << " without a face); test: " << test.images << " images (" << test.without_face << " without a face)\n"
                  << std::left << std::setw(8) << "method" << std::right << std::setw(10) << "accuracy" << std::setw(10)
                  << "faces" << std::setw(12) << "train s" << std::setw(12) << "ms/face" << "\n";
    std::vector<JsonObject> rows;
    for (ClassifierKind kind : methods) {
        ClassifierBankParams params = base;
        params.classifier.kind = kind;
        ClassifierBank bank(params);
        for (std::size_t p = 0; p < train.names.size(); ++p)
            if (!train.faces[p].empty()) bank.add_faces(train.names[p], train.faces[p]);
        auto t0 = Clock::now();
        bank.train();
        const double train_s = seconds_since(t0);
        int correct = 0, total = 0, not_enrolled = 0;
        t0 = Clock::now();
        for (std::size_t p = 0; p < test.names.size(); ++p) {
            if (!bank.contains(test.names[p])) {
                not_enrolled += int(test.faces[p].size());
                continue;
            }
            for (const cv::Mat& face : test.faces[p]) {
                const Decision d = bank.decide(face);
                correct += d.name == test.names[p];
                ++total;
            }
        }
        const double ms = 1000.0 * seconds_since(t0) / std::max(total, 1);
        const double accuracy = double(correct) / std::max(total, 1);
        JsonObject row;
        row.add("method", to_string(kind)).add("accuracy", accuracy).add("faces", total);
        row.add("not_enrolled", not_enrolled).add("train_seconds", train_s).add("ms_per_face", ms);
        rows.push_back(row);
        if (!json)
            std::cout << std::left << std::setw(8) << to_string(kind) << std::right << std::fixed << std::setprecision(3)
                      << std::setw(10) << accuracy << std::setw(10) << total << std::setw(12) << train_s << std::setw(12)
                      << ms << std::endl;
    }
    result.add("methods", rows);
    if (json) std::cout << result.str() << "\n";
    return 0;
}

int cmd_eval_unknown(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--methods"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const auto methods = parse_methods(args.get("--methods", "ehmm"));
    const bool json = args.flag("--json");
    const FaceSet set = load_cropped_faces(root / "orl");
    const std::size_t people = set.faces.size();
    if (people < 10) throw FileError((root / "orl").string(), "ORL with fewer than 10 people");
    for (std::size_t p = 0; p < people; ++p)
        if (set.faces[p].size() < 10) throw FileError((root / "orl" / set.names[p]).string(), "fewer than 10 images");
    const std::size_t group = 5, groups = people / group;

    JsonObject result;
    result.add("dataset", "orl").add("known_people", int(people - group)).add("unknown_people", int(group));
    result.add("groups", int(groups));
    std::vector<JsonObject> rows;
    for (ClassifierKind kind : methods) {
        // Statistics of every probe, pooled over the rotations.
        std::vector<double> known_best, unknown_best, known_var, unknown_var, known_margin, unknown_margin;
        int identified = 0;
        for (std::size_t g = 0; g < groups; ++g) {
            ClassifierBankParams params;
            params.normalizer = NormalizerParams::cropped();
            params.classifier.kind = kind;
            ClassifierBank bank(params);
            for (std::size_t p = 0; p < people; ++p)
                if (p / group != g) bank.add_faces(set.names[p], {set.faces[p].begin(), set.faces[p].begin() + 5});
            bank.train();
            for (std::size_t p = 0; p < people; ++p) {
                const bool known = p / group != g;
                for (std::size_t i = known ? 5 : 0; i < 10; ++i) {
                    const Decision d = bank.decide(set.faces[p][i]);
                    (known ? known_best : unknown_best).push_back(d.score);
                    (known ? known_var : unknown_var).push_back(d.variance);
                    (known ? known_margin : unknown_margin).push_back(d.margin);
                    if (known) identified += d.name == set.names[p];
                }
            }
        }
        JsonObject row;
        row.add("method", to_string(kind)).add("known_probes", known_best.size()).add("unknown_probes", unknown_best.size());
        row.add("identification_accuracy", double(identified) / double(known_best.size()));
        if (!json)
            std::cout << to_string(kind) << ": " << known_best.size() << " known probes, " << unknown_best.size()
                      << " unknown probes, identification accuracy " << std::fixed << std::setprecision(3)
                      << double(identified) / double(known_best.size()) << "\n";
        for (const auto& [rule, known, unknown] :
             {std::tuple{"min_score", &known_best, &unknown_best}, std::tuple{"min_variance", &known_var, &unknown_var},
              std::tuple{"min_margin", &known_margin, &unknown_margin}}) {
            std::vector<JsonObject> points;
            for (double share : {0.80, 0.90, 0.95, 0.99}) {
                const double t = threshold_for_acceptance(*known, share);
                JsonObject pt;
                pt.add("known_accepted", acceptance_rate(*known, t)).add("threshold", t);
                pt.add("false_accept", acceptance_rate(*unknown, t));
                points.push_back(pt);
            }
            const double t95 = threshold_for_acceptance(*known, 0.95);
            const EqualErrorRate eer = equal_error_rate(*known, *unknown);
            JsonObject r;
            r.add("threshold_at_95", t95).add("false_accept_at_95", acceptance_rate(*unknown, t95));
            r.add("eer", eer.rate).add("eer_threshold", eer.threshold).add("operating_points", points);
            row.add(rule, r);
            if (!json) {
                std::cout << "  " << std::left << std::setw(13) << rule << std::right << " threshold " << std::setprecision(4)
                          << t95 << " keeps 95% of known faces, false accepts " << std::setprecision(3)
                          << acceptance_rate(*unknown, t95) << "; EER " << eer.rate << " at " << std::setprecision(4)
                          << eer.threshold << "\n";
                for (const double share : {0.80, 0.90, 0.99}) {
                    const double t = threshold_for_acceptance(*known, share);
                    std::cout << "    known accepted " << std::setprecision(3) << acceptance_rate(*known, t) << " at "
                              << std::setprecision(4) << t << ": false accepts " << std::setprecision(3)
                              << acceptance_rate(*unknown, t) << "\n";
                }
            }
        }
        rows.push_back(row);
    }
    result.add("methods", rows);
    if (json) std::cout << result.str() << "\n";
    return 0;
}

}  // namespace facesocial::cli
