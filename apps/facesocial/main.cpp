// facesocial: command-line front end of the FaceSocial library.
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/error.hpp"
#include "facesocial/version.hpp"

namespace {

const char* const kUsage = R"(usage: facesocial <command> [options]

commands:
  detect IMAGE|FOLDER [--profile] [--no-skin-filter] [--out DIR] [--json]
        detect faces, skin-filter and normalise them; --out writes annotated images and face crops
  eval detection [--data DIR] [--json]
        detector recall / false positives on dlib_faces and one-face share on Caltech faces
  eval orl [--data DIR] [--methods ehmm,eigen,fisher,lbph] [--splits N] [--json]
        ORL protocol: canonical split and N seeded random 5/5 splits per method
  eval identify --train DIR --test DIR [--methods LIST] [--detect] [--json]
        accuracy, training time and ms per face for two folders of one sub-folder per person
  eval unknown [--data DIR] [--methods LIST] [--json]
        open set on ORL: 35 known / 5 unknown people in 8 rotations; false accepts of the
        min-score, min-variance and min-margin rules at 95% known acceptance, equal-error rates
  eval window [--data DIR] [--enrol K] [--far PIXELS] [--out DIR] [--json]
        accuracy against the evidence window (1-50 frames; moving average, decay, vote) on
        Essex talking sequences and ORL sequences; writes window.csv / window.png
  eval threshold [--data DIR] [--window N] [--out DIR] [--json]
        accuracy and false positives against the unknown thresholds, per frame and accumulated,
        with held-out ORL people and Essex's unlabelled faces as strangers; CSV + PNG curves
  eval throughput [--data DIR] [--frames N] [--profile] [--json]
        frames and faces per second of the whole pipeline with 40 people enrolled
  watch --bank FILE SOURCE [--window N] [--mode average|decay|vote] [--out video.mp4]
        [--events events.jsonl] [--profile] [--max-frames N] [--json]
        run the live pipeline on a camera index, video file, stream URL or frame folder
  tag --bank FILE PHOTO [--tags tags.json] [--graph graph.json] [--out annotated.jpg] [--enrol]
      [--bonus B] [--no-profile] [--json]
        tags -> faces (nearest face; a profile refuses the tag), --enrol adds them as training
        samples; untagged faces -> names without and with the friend prior
  eval tagging [--data DIR] [--photos N] [--seed S] [--enrol K] [--json]
        group-photo tagging with / without the friend prior (and a shuffled graph), friendship
        suggestions, and the tag-to-face step on dlib_faces
  eval training-policy [--data DIR] [--samples N] [--wrong SHARE] [--seed S] [--json]
        accuracy and training time of training-set policies (size cap, newest or spread,
        pruning of wrongly tagged samples) on ORL
  enrol --bank FILE --person NAME IMAGES|FOLDER [--detect] [--train] [--method KIND] [--mask|--no-mask]
        add face images to a person's training set (creates the bank file if needed; --method
        and --mask choose the classifier and the elliptical mask of a new bank)
  train --bank FILE [--person NAME] [--json]
        train everyone whose training set changed, or one person
  forget --bank FILE --person NAME
        remove a person's training set and model
  recognize --bank FILE IMAGE|FOLDER [--detect] [--top K] [--min-score S] [--min-variance V]
              [--min-margin M] [--json]
        name the face (whole image, or every detected face) with the top K candidates
  version
        print the library version

The data root is --data DIR or $FACESOCIAL_DATA.
Exit codes: 0 success, 1 file or data error, 2 usage error or invalid input.
)";

}  // namespace

int main(int argc, char** argv) {
    using namespace facesocial;
    // Errors reach the user as exceptions with their own message; OpenCV's backend probing
    // (GStreamer, V4L2) would otherwise print several lines for every missing camera or file.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    cv::setNumThreads(1);  // the library does its own parallelism (TBB); keep OpenCV's out of the way
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
        std::cout << kUsage;
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "detect") return cli::cmd_detect(args);
        if (command == "eval") return cli::cmd_eval(args);
        if (command == "enrol" || command == "enroll") return cli::cmd_enrol(args);
        if (command == "train") return cli::cmd_train(args);
        if (command == "forget") return cli::cmd_forget(args);
        if (command == "recognize" || command == "recognise") return cli::cmd_recognize(args);
        if (command == "watch") return cli::cmd_watch(args);
        if (command == "tag") return cli::cmd_tag(args);
        if (command == "version") {
            std::cout << "facesocial " << FACESOCIAL_VERSION_STRING << "\n";
            return 0;
        }
        throw cli::UsageError("unknown command '" + command + "'");
    } catch (const cli::UsageError& e) {
        std::cerr << "facesocial: " << e.what() << "\n\n" << kUsage;
        return 2;
    } catch (const FileError& e) {
        std::cerr << "facesocial: error: " << e.what() << "\n";
        return 1;
    } catch (const std::invalid_argument& e) {
        std::cerr << "facesocial: invalid input: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "facesocial: error: " << e.what() << "\n";
        return 1;
    }
}
