// facesocial eval detection: detector accuracy and speed on dlib_faces (hand-drawn boxes) and the
// one-face share on Caltech Faces 1999 (one person per photo).
#include <chrono>
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/detection_eval.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

namespace {

struct Config {
    std::string name;
    bool profile;
    bool skin;
};

const Config kConfigs[] = {
    {"frontal", false, false},
    {"frontal+skin", false, true},
    {"frontal+profile+skin", true, true},
};

FrontEndParams params_for(const Config& c) {
    FrontEndParams p;
    p.use_profile = c.profile;
    p.use_skin_filter = c.skin;
    p.normalize = false;
    return p;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int cmd_eval_detection(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--iou"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const double min_iou = args.get_double("--iou", 0.5);
    const bool json = args.flag("--json");

    const auto dlib = load_dlib_faces(root);
    std::vector<cv::Mat> dlib_images;
    int truth_faces = 0;
    for (const auto& a : dlib) {
        dlib_images.push_back(load_image(a.file));
        truth_faces += int(a.faces.size());
    }
    // dogs.jpg: no human face, every detection there is a false positive.
    const cv::Mat negative = load_image(root / "dlib_faces" / "dogs.jpg");
    const auto caltech_files = list_images(root / "caltech_faces1999_partial" / "images");
    std::vector<cv::Mat> caltech_images;
    for (const auto& f : caltech_files) caltech_images.push_back(load_image(f));

    JsonObject result;
    result.add("dataset", "dlib_faces").add("images", int(dlib.size())).add("truth_faces", truth_faces);
    result.add("min_iou", min_iou);
    std::vector<JsonObject> rows;
    if (!json) {
        std::cout << "dlib_faces: " << dlib.size() << " images, " << truth_faces << " hand-drawn faces, IoU >= "
                  << min_iou << "; FPdogs = detections on dogs.jpg (no person)\n";
        std::cout << std::left << std::setw(24) << "config" << std::right << std::setw(6) << "TP" << std::setw(8)
                  << "recall" << std::setw(6) << "FP" << std::setw(8) << "FPdogs" << std::setw(10) << "ms/img" << std::setw(16)
                  << "caltech 1-face" << std::setw(10) << "ms/img" << "\n";
    }
    for (const Config& c : kConfigs) {
        const FrontEnd front_end(params_for(c));
        DetectionCounts counts;
        auto t0 = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < dlib.size(); ++i) {
            const FrontEndResult r = front_end.process(dlib_images[i]);
            std::vector<Detection> kept;
            for (const auto& f : r.faces) kept.push_back(f.detection);
            counts += match_detections(dlib[i].faces, kept, min_iou);
        }
        const double dlib_ms = ms_since(t0) / double(dlib.size());
        const int negative_fp = int(front_end.process(negative).faces.size());

        int exactly_one = 0;
        t0 = std::chrono::steady_clock::now();
        for (const cv::Mat& img : caltech_images) exactly_one += front_end.process(img).faces.size() == 1;
        const double caltech_ms = ms_since(t0) / double(caltech_images.size());
        const double one_share = double(exactly_one) / double(caltech_images.size());

        JsonObject row;
        row.add("config", c.name).add("true_positives", counts.true_positives).add("recall", counts.recall());
        row.add("false_positives", counts.false_positives).add("ms_per_image", dlib_ms);
        row.add("false_positives_dogs", negative_fp);
        row.add("caltech_images", int(caltech_images.size())).add("caltech_exactly_one", exactly_one);
        row.add("caltech_exactly_one_share", one_share).add("caltech_ms_per_image", caltech_ms);
        rows.push_back(row);
        if (!json) {
            std::cout << std::left << std::setw(24) << c.name << std::right << std::setw(6) << counts.true_positives
                      << std::setw(8) << std::fixed << std::setprecision(3) << counts.recall() << std::setw(6)
                      << counts.false_positives << std::setw(8) << negative_fp << std::setw(10) << std::setprecision(1) << dlib_ms << std::setw(9)
                      << exactly_one << "/" << caltech_images.size() << std::setw(10) << caltech_ms << "\n";
        }
    }
    result.add("configs", rows);
    if (json) std::cout << result.str() << "\n";
    return 0;
}

int cmd_eval(const std::vector<std::string>& argv) {
    if (argv.empty()) throw UsageError("eval: expected a suite name (detection, orl, identify, unknown, window, threshold, throughput, tagging, training-policy)");
    const std::vector<std::string> rest(argv.begin() + 1, argv.end());
    if (argv[0] == "detection") return cmd_eval_detection(rest);
    if (argv[0] == "orl") return cmd_eval_orl(rest);
    if (argv[0] == "identify") return cmd_eval_identify(rest);
    if (argv[0] == "unknown") return cmd_eval_unknown(rest);
    if (argv[0] == "window") return cmd_eval_window(rest);
    if (argv[0] == "threshold") return cmd_eval_threshold(rest);
    if (argv[0] == "throughput") return cmd_eval_throughput(rest);
    if (argv[0] == "tagging") return cmd_eval_tagging(rest);
    if (argv[0] == "training-policy") return cmd_eval_training_policy(rest);
    throw UsageError("eval: unknown suite '" + argv[0] + "'");
}

}  // namespace facesocial::cli
