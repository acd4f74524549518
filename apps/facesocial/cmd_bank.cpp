// The bank commands: enrol, train, forget, recognize.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "commands.hpp"
#include "face_input.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

namespace {

std::string require_bank(const Args& args, const char* command) {
    const std::string bank = args.get("--bank");
    if (bank.empty()) throw UsageError(std::string(command) + ": expected --bank FILE");
    return bank;
}

std::string require_person(const Args& args, const char* command) {
    const std::string person = args.get("--person");
    if (person.empty()) throw UsageError(std::string(command) + ": expected --person NAME");
    return person;
}

/// A new bank from the enrol options (kind, mask), or the existing file.
ClassifierBank open_or_create(const std::string& path, const Args& args) {
    std::error_code ec;
    if (fs::exists(path, ec)) {
        if (args.has("--method") || args.flag("--mask") || args.flag("--no-mask"))
            std::cerr << "note: " << path << " exists; --method / --mask apply only when a bank is created\n";
        return ClassifierBank::load(path);
    }
    ClassifierBankParams params;
    params.classifier.kind = classifier_kind_from_string(args.get("--method", "ehmm"));
    // Cropped faces (no --detect) do best without the mask; detector boxes hold background.
    params.normalizer.elliptical_mask = args.flag("--mask") || (args.flag("--detect") && !args.flag("--no-mask"));
    return ClassifierBank(params);
}

void print_stale(const ClassifierBank& bank) {
    const auto stale = bank.stale();
    if (stale.empty()) return;
    std::cout << stale.size() << " person(s) need training:";
    for (const auto& n : stale) std::cout << " " << n;
    std::cout << "  (facesocial train --bank FILE)\n";
}

}  // namespace

int cmd_enrol(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--person", "--method"}, {"--detect", "--train", "--mask", "--no-mask", "--json"});
    const std::string path = require_bank(args, "enrol");
    const std::string person = require_person(args, "enrol");
    if (args.positional().empty()) throw UsageError("enrol: expected IMAGES or FOLDER");
    ClassifierBank bank = open_or_create(path, args);
    const auto front_end = make_front_end(args.flag("--detect"));
    std::vector<cv::Mat> faces;
    int skipped = 0;
    for (const fs::path& file : expand_inputs(args.positional())) {
        const auto found = faces_of(load_image(file, ImageColor::Any), bank, front_end.get());
        if (found.empty()) {
            std::cerr << "note: no face found in " << file.string() << "; skipped\n";
            ++skipped;
            continue;
        }
        faces.push_back(found.front().face);  // with detection, the largest face is the person
    }
    if (faces.empty()) throw FileError(path, "no face to enrol for '" + person + "'; the bank is unchanged");
    bank.add_faces(person, faces);
    if (args.flag("--train")) bank.train(person);
    bank.save(path);
    if (args.flag("--json")) {
        JsonObject o;
        o.add("bank", path).add("person", person).add("added", faces.size()).add("skipped", skipped);
        o.add("faces", bank.face_count(person)).add("trained", bank.is_trained(person));
        std::cout << o.str() << "\n";
    } else {
        std::cout << "enrolled " << faces.size() << " face(s) of " << person << " (" << bank.face_count(person)
                  << " in all) in " << path << "\n";
        print_stale(bank);
    }
    return 0;
}

int cmd_train(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--person"}, {"--json"});
    const std::string path = require_bank(args, "train");
    ClassifierBank bank = ClassifierBank::load(path);
    std::vector<std::string> trained;
    if (args.has("--person")) {
        bank.train(args.get("--person"));
        trained.push_back(args.get("--person"));
    } else {
        trained = bank.train();
    }
    bank.save(path);
    if (args.flag("--json")) {
        JsonObject o;
        std::string list = "[";
        for (std::size_t i = 0; i < trained.size(); ++i) {
            if (i) list += ',';
            list += quote(trained[i]);
        }
        o.add("bank", path).raw("trained", list + "]");
        std::cout << o.str() << "\n";
    } else {
        std::cout << "trained " << trained.size() << " person(s)";
        for (const auto& n : trained) std::cout << " " << n;
        std::cout << "\n";
    }
    return 0;
}

int cmd_forget(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--person"}, {});
    const std::string path = require_bank(args, "forget");
    const std::string person = require_person(args, "forget");
    ClassifierBank bank = ClassifierBank::load(path);
    bank.remove_person(person);
    bank.save(path);
    std::cout << "forgot " << person << "; " << bank.people().size() << " person(s) left in " << path << "\n";
    return 0;
}

int cmd_recognize(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--top", "--min-score", "--min-variance", "--min-margin"}, {"--detect", "--json"});
    const std::string path = require_bank(args, "recognize");
    if (args.positional().empty()) throw UsageError("recognize: expected IMAGE or FOLDER");
    const int top = args.get_int("--top", 3);
    if (top < 1) throw UsageError("--top: expected >= 1");
    ClassifierBank bank = ClassifierBank::load(path);
    UnknownRule rule = bank.unknown_rule();
    rule.min_score = args.get_double("--min-score", rule.min_score);
    rule.min_variance = args.get_double("--min-variance", rule.min_variance);
    rule.min_margin = args.get_double("--min-margin", rule.min_margin);
    rule.min_margin = args.get_double("--min-margin", rule.min_margin);
    bank.set_unknown_rule(rule);
    if (bank.trained_people().empty())
        throw FileError(path, "no trained person in the bank (run facesocial train)");
    const auto front_end = make_front_end(args.flag("--detect"));
    const bool json = args.flag("--json");
    std::vector<JsonObject> results;
    for (const fs::path& file : expand_inputs(args.positional())) {
        const auto found = faces_of(load_image(file, ImageColor::Any), bank, front_end.get());
        if (!json && found.empty()) std::cout << file.string() << ": no face\n";
        for (std::size_t i = 0; i < found.size(); ++i) {
            const Decision d = bank.decide(found[i].face);
            const std::size_t k = std::min<std::size_t>(std::size_t(top), d.ranked.size());
            if (json) {
                std::vector<JsonObject> cands;
                for (std::size_t c = 0; c < k; ++c) {
                    JsonObject o;
                    o.add("name", d.ranked[c].name).add("score", d.ranked[c].score);
                    cands.push_back(o);
                }
                JsonObject box, r;
                box.add("x", found[i].box.x).add("y", found[i].box.y).add("w", found[i].box.width).add("h", found[i].box.height);
                r.add("file", file.string()).add("face", int(i)).add("box", box).add("known", d.known);
                r.add("name", d.known ? d.name : std::string("unknown")).add("score", d.score).add("variance", d.variance);
                r.add("margin", d.margin);
                r.add("candidates", cands);
                results.push_back(r);
            } else {
                std::cout << file.string();
                if (front_end) std::cout << " face " << i;
                std::cout << ": " << (d.known ? d.name : "unknown") << std::fixed << std::setprecision(3)
                          << "  (score " << d.score << ", variance " << d.variance << ", margin " << d.margin
                          << ")  candidates:";
                for (std::size_t c = 0; c < k; ++c) std::cout << " " << d.ranked[c].name << " " << d.ranked[c].score;
                std::cout << "\n";
            }
        }
    }
    if (json) {
        JsonObject o;
        o.add("bank", path).add("results", results);
        std::cout << o.str() << "\n";
    }
    return 0;
}

}  // namespace facesocial::cli
