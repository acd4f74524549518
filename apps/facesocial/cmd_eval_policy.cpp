// facesocial eval training-policy: accuracy and training time of training-set policies (size
// cap, recency or even spread, pruning of wrongly tagged samples) on ORL.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <random>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/face_augment.hpp"
#include "facesocial/training_set.hpp"

namespace facesocial::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct PolicyRow {
    std::string name;
    TrainingPolicy policy;
};

}  // namespace

int cmd_eval_training_policy(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--samples", "--wrong", "--seed"}, {"--json"});
    const auto root = data_dir(args.get("--data"));
    const int per_person = args.get_int("--samples", 100);
    const double wrong_share = args.get_double("--wrong", 0.1);
    const uint32_t seed = uint32_t(args.get_int("--seed", 5));
    if (per_person < 5 || per_person > 2000 || !(wrong_share >= 0 && wrong_share < 0.5))
        throw UsageError("eval training-policy: expected --samples in [5, 2000] and --wrong in [0, 0.5)");
    const FaceSet orl = load_cropped_faces(root / "orl");
    const std::size_t P = orl.names.size();

    // Each person's history: images 1-5 in time order (image 1 oldest), each followed by small
    // variations of itself (the frames of that encounter), per_person samples in all; a share
    // of them are wrongly tagged social photos (another person's face).
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(0, 1);
    std::uniform_int_distribution<std::size_t> other(0, P - 2), image(0, 4);
    std::vector<std::vector<TrainingSample>> history(P);
    int wrong = 0;
    for (std::size_t p = 0; p < P; ++p) {
        for (int i = 0; i < 5; ++i) {
            const int n = per_person / 5 + (i < per_person % 5 ? 1 : 0);
            const auto frames = augment_faces({orl.faces[p][std::size_t(i)]}, std::size_t(n), {}, uint32_t(seed * 1000 + p * 10 + std::size_t(i)));
            for (int k = 0; k < n; ++k) {
                TrainingSample s{frames[std::size_t(k)], SampleSource::Camera, 1000.0 * i + k, "session" + std::to_string(i + 1)};
                if (uni(rng) < wrong_share) {
                    std::size_t q = other(rng);
                    if (q >= p) ++q;
                    s.face = orl.faces[q][image(rng)];
                    s.source = SampleSource::SocialPhoto;
                    ++wrong;
                }
                history[p].push_back(s);
            }
        }
    }

    ClassifierBankParams bp;
    bp.normalizer = NormalizerParams::cropped();
    auto evaluate = [&](const TrainingPolicy& policy, const ClassifierBank* others, double& train_s, double& select_s,
                        std::size_t& pruned, std::size_t& wrong_kept) {
        ClassifierBank bank(bp);
        pruned = wrong_kept = 0;
        const auto t0 = Clock::now();
        for (std::size_t p = 0; p < P; ++p) {
            const SelectionReport r = select_training_samples(history[p], policy, bp.classifier.ehmm, others, orl.names[p]);
            pruned += r.pruned.size();
            std::vector<cv::Mat> faces;
            for (std::size_t i : r.kept) {
                faces.push_back(history[p][i].face);
                wrong_kept += history[p][i].source == SampleSource::SocialPhoto;
            }
            bank.add_faces(orl.names[p], faces);
        }
        const auto t1 = Clock::now();
        bank.train();
        train_s = std::chrono::duration<double>(Clock::now() - t1).count();
        select_s = std::chrono::duration<double>(t1 - t0).count();
        int ok = 0;
        for (std::size_t p = 0; p < P; ++p)
            for (std::size_t i = 5; i < 10; ++i) ok += bank.decide(orl.faces[p][i]).name == orl.names[p];
        return std::pair<double, ClassifierBank>(double(ok) / double(P * 5), std::move(bank));
    };

    std::vector<PolicyRow> rows;
    for (std::size_t cap : {std::size_t(5), std::size_t(10), std::size_t(30), std::size_t(100)})
        for (bool recent : {true, false}) {
            if (cap >= std::size_t(per_person) && !recent) continue;
            TrainingPolicy t;
            t.max_size = cap >= std::size_t(per_person) ? 0 : cap;
            t.prefer_recent = recent;
            rows.push_back({(t.max_size ? "cap " + std::to_string(cap) : std::string("all")) + (t.max_size ? (recent ? ", newest" : ", spread") : ""), t});
        }
    // The reference bank for pruning: everyone from all their samples, unpruned.
    double ts = 0, ss = 0;
    std::size_t pr = 0, wk = 0;
    TrainingPolicy all;
    all.max_size = 0;
    const auto reference = evaluate(all, nullptr, ts, ss, pr, wk);
    for (std::size_t cap : {std::size_t(30), std::size_t(0)}) {
        TrainingPolicy t;
        t.max_size = cap;
        t.prefer_recent = false;
        t.prune_sigma = 2.0;
        rows.push_back({(cap ? "cap 30, spread" : std::string("all")) + ", pruned (2 sigma)", t});
    }

    JsonObject result;
    result.add("people", P).add("samples_per_person", per_person).add("wrong_tags", wrong).add("seed", long(seed));
    std::vector<JsonObject> out;
    if (!args.flag("--json"))
        std::cout << P << " ORL people, " << per_person << " samples each from images 1-5 (" << wrong
                  << " wrongly tagged faces of other people); tested on images 6-10\n"
                  << std::left << std::setw(34) << "policy" << std::right << std::setw(10) << "accuracy" << std::setw(10)
                  << "train s" << std::setw(11) << "select s" << std::setw(9) << "pruned" << std::setw(12) << "wrong kept"
                  << "\n";
    for (const PolicyRow& row : rows) {
        double train_s = 0, select_s = 0;
        std::size_t pruned = 0, wrong_kept = 0;
        const bool prune = row.policy.prune_sigma > 0;
        const double acc = evaluate(row.policy, prune ? &reference.second : nullptr, train_s, select_s, pruned, wrong_kept).first;
        JsonObject o;
        o.add("policy", row.name).add("accuracy", acc).add("train_seconds", train_s).add("select_seconds", select_s);
        o.add("pruned", pruned).add("wrong_kept", wrong_kept);
        out.push_back(o);
        if (!args.flag("--json"))
            std::cout << std::left << std::setw(34) << row.name << std::right << std::fixed << std::setprecision(3)
                      << std::setw(10) << acc << std::setw(10) << train_s << std::setw(11) << select_s << std::setw(9) << pruned
                      << std::setw(12) << wrong_kept << "\n";
    }
    result.add("policies", out);
    if (args.flag("--json")) std::cout << result.str() << "\n";
    return 0;
}

}  // namespace facesocial::cli
