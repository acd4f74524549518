// facesocial: command-line front end of the FaceSocial library.
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

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
  version
        print the library version

The data root is --data DIR or $FACESOCIAL_DATA.
Exit codes: 0 success, 1 file or data error, 2 usage error or invalid input.
)";

}  // namespace

int main(int argc, char** argv) {
    using namespace facesocial;
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
