// facesocial tag (a photo's tags -> training samples, untagged faces -> names with and without
// the friend prior) and eval tagging (composed group photos with a generated social graph, and
// the tag-to-face step on dlib_faces).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <random>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/friend_tagging.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/photo_tags.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json read_json(const std::string& path, const char* what) {
    std::ifstream in(path);
    if (!in) throw FileError(path, std::string("cannot open the ") + what + " file");
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw FileError(path, std::string("not a valid JSON ") + what + " file: " + e.what());
    }
}

/// tags.json: [{"person": "ann", "x": 120, "y": 80}, ...] (or {"tags": [...]}).
std::vector<PhotoTag> read_tags(const std::string& path) {
    json j = read_json(path, "tags");
    if (j.is_object() && j.contains("tags")) j = j["tags"];
    if (!j.is_array()) throw FileError(path, "expected a list of tags {\"person\", \"x\", \"y\"}");
    std::vector<PhotoTag> out;
    for (const json& t : j) {
        if (!t.is_object() || !t.contains("person") || !t["person"].is_string() || !t.contains("x") || !t["x"].is_number() ||
            !t.contains("y") || !t["y"].is_number())
            throw FileError(path, "expected every tag as {\"person\": name, \"x\": number, \"y\": number}, got " + t.dump());
        out.push_back({t["person"].get<std::string>(), {t["x"].get<float>(), t["y"].get<float>()}});
    }
    return out;
}

/// graph.json: {"friendships": [["ann", "bob"], ...]} or {"ann": ["bob", ...], ...}.
InMemorySocialGraph read_graph(const std::string& path) {
    const json j = read_json(path, "graph");
    InMemorySocialGraph g;
    if (!j.is_object()) throw FileError(path, "expected an object: {\"friendships\": [[a, b], ...]} or {person: [friends]}");
    if (j.contains("friendships")) {
        for (const json& pair : j["friendships"]) {
            if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_string())
                throw FileError(path, "expected friendships as [name, name] pairs, got " + pair.dump());
            g.add_friendship(pair[0].get<std::string>(), pair[1].get<std::string>());
        }
        return g;
    }
    for (const auto& [person, friends] : j.items()) {
        g.add_person(person);
        if (!friends.is_array()) throw FileError(path, "expected a list of friends for '" + person + "'");
        for (const json& f : friends) {
            if (!f.is_string()) throw FileError(path, "expected names in the friends of '" + person + "'");
            g.add_friendship(person, f.get<std::string>());
        }
    }
    return g;
}

}  // namespace

int cmd_tag(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--tags", "--graph", "--out", "--bonus"}, {"--json", "--enrol", "--no-profile"});
    if (!args.has("--bank") || args.positional().size() != 1) throw UsageError("tag: expected --bank FILE and one PHOTO");
    const std::string bank_path = args.get("--bank");
    ClassifierBank bank = ClassifierBank::load(bank_path);
    const cv::Mat photo = load_image(args.positional()[0]);
    const std::vector<PhotoTag> tags = args.has("--tags") ? read_tags(args.get("--tags")) : std::vector<PhotoTag>{};
    std::unique_ptr<InMemorySocialGraph> graph;
    if (args.has("--graph")) graph = std::make_unique<InMemorySocialGraph>(read_graph(args.get("--graph")));
    FriendTaggingParams tp;
    tp.friend_bonus = args.get_double("--bonus", tp.friend_bonus);
    tp.unknown = bank.unknown_rule();

    FrontEndParams fp;
    fp.use_profile = !args.flag("--no-profile");
    fp.normalizer = bank.params().normalizer;
    const FrontEndResult found = FrontEnd(fp).process(photo);
    std::vector<Detection> detections;
    for (const FrontEndFace& f : found.faces) detections.push_back(f.detection);
    const std::vector<TagResolution> resolved =
        resolve_tags(detections, tags, photo.size(), {}, graph ? graph->people() : std::vector<std::string>{});

    // Tagged faces become training samples; the rest are recognised.
    std::vector<char> tagged(detections.size(), 0);
    const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    std::vector<std::string> present;
    for (const TagResolution& r : resolved)
        if (r.outcome == TagOutcome::Resolved) {
            tagged[std::size_t(r.face)] = 1;
            present.push_back(r.tag.person);
            if (args.flag("--enrol"))
                bank.add_samples(r.tag.person, {{found.faces[std::size_t(r.face)].face.pixels, SampleSource::SocialPhoto, now,
                                                 fs::path(args.positional()[0]).filename().string()}});
        }
    std::vector<std::size_t> untagged;
    std::vector<BankScores> scores;
    for (std::size_t i = 0; i < detections.size(); ++i)
        if (!tagged[i] && !is_profile(detections[i].pose)) {
            untagged.push_back(i);
            scores.push_back(bank.scores(found.faces[i].face.pixels));
        }
    FriendTaggingParams alone = tp;
    alone.friend_bonus = 0;
    const std::vector<FaceTag> without = tag_faces(scores, nullptr, alone, present);
    const std::vector<FaceTag> with = tag_faces(scores, graph.get(), tp, present);
    if (args.flag("--enrol")) bank.save(bank_path);

    if (args.has("--out")) {
        cv::Mat canvas = photo.clone();
        for (std::size_t i = 0; i < detections.size(); ++i) {
            const cv::Scalar c = is_profile(detections[i].pose) ? cv::Scalar(255, 120, 0) : cv::Scalar(0, 200, 0);
            cv::rectangle(canvas, detections[i].box, c, 2);
        }
        for (const TagResolution& r : resolved) {
            const cv::Scalar c = r.outcome == TagOutcome::Resolved ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 230);
            cv::drawMarker(canvas, r.tag.point, c, cv::MARKER_CROSS, 14, 2);
            cv::putText(canvas, r.tag.person, r.tag.point + cv::Point2f(8, -8), cv::FONT_HERSHEY_SIMPLEX, 0.5, c, 1, cv::LINE_AA);
        }
        for (std::size_t k = 0; k < untagged.size(); ++k) {
            const cv::Rect& b = detections[untagged[k]].box;
            const std::string label = with[k].known ? with[k].name : "unknown";
            cv::putText(canvas, label, {b.x, b.y + b.height + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 220, 255), 1,
                        cv::LINE_AA);
        }
        save_image(args.get("--out"), canvas);
    }

    JsonObject result;
    result.add("photo", args.positional()[0]).add("faces", detections.size());
    std::vector<JsonObject> tag_rows, face_rows;
    for (const TagResolution& r : resolved) {
        JsonObject o;
        o.add("person", r.tag.person).add("outcome", to_string(r.outcome)).add("face", r.face).add("distance", r.distance);
        o.add("reason", r.reason);
        tag_rows.push_back(o);
    }
    for (std::size_t k = 0; k < untagged.size(); ++k) {
        const cv::Rect& b = detections[untagged[k]].box;
        JsonObject o;
        o.add("face", int(untagged[k])).add("box", std::vector<double>{double(b.x), double(b.y), double(b.width), double(b.height)});
        o.add("name", without[k].known ? without[k].name : "unknown");
        o.add("name_with_friends", with[k].known ? with[k].name : "unknown").add("friend_bonus", with[k].bonus);
        face_rows.push_back(o);
    }
    result.add("tags", tag_rows).add("untagged", face_rows).add("enrolled", args.flag("--enrol"));
    if (args.flag("--json")) {
        std::cout << result.str() << "\n";
        return 0;
    }
    std::cout << detections.size() << " face(s) detected\n";
    for (const TagResolution& r : resolved)
        std::cout << "tag " << r.tag.person << ": " << to_string(r.outcome) << (r.face >= 0 ? " (face " + std::to_string(r.face) + ")" : "")
                  << " - " << r.reason << (r.outcome == TagOutcome::Resolved && args.flag("--enrol") ? "; enrolled" : "") << "\n";
    for (std::size_t k = 0; k < untagged.size(); ++k)
        std::cout << "face " << untagged[k] << ": " << (without[k].known ? without[k].name : "unknown")
                  << " (recognition alone), " << (with[k].known ? with[k].name : "unknown") << " (with the friend prior)\n";
    return 0;
}

// ---------------------------------------------------------------------------------------------
// eval tagging

namespace {

struct Composed {
    std::vector<std::vector<std::size_t>> people;  // per photo: person index per detected face
    std::vector<std::vector<BankScores>> scores;   // per photo: scores per detected face
    int placed = 0, detected = 0;
};

/// ORL face i of person p, doubled (the cascade finds faces of this size reliably).
cv::Mat big_face(const PersonImages& p, std::size_t i) {
    const cv::Mat f = load_image(p.images[i], ImageColor::Bgr);
    cv::Mat out;
    cv::resize(f, out, {}, 2.0, 2.0, cv::INTER_LINEAR);
    return out;
}

/// Places faces in a row on a grey canvas and returns the canvas and where each face went.
cv::Mat compose(const std::vector<cv::Mat>& faces, std::vector<cv::Rect>& where) {
    const int gap = 24, w = faces.empty() ? 0 : faces[0].cols, h = faces.empty() ? 0 : faces[0].rows;
    cv::Mat canvas(h + 2 * gap, int(faces.size()) * (w + gap) + gap, CV_8UC3, cv::Scalar(120, 120, 120));  // grey, like the faces: the skin filter stands aside
    where.clear();
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const cv::Rect r(gap + int(i) * (w + gap), gap, w, h);
        faces[i].copyTo(canvas(r));
        where.push_back(r);
    }
    return canvas;
}

}  // namespace

int cmd_eval_tagging(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--photos", "--seed", "--enrol"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const bool json_out = args.flag("--json");
    const int photos = args.get_int("--photos", 200);
    const uint32_t seed = uint32_t(args.get_int("--seed", 2026));
    const int enrol = args.get_int("--enrol", 2);
    if (photos < 1 || enrol < 1 || enrol > 5) throw UsageError("eval tagging: expected --photos >= 1 and --enrol in [1, 5]");

    // People, bank and the front end (frontal, skin filter, elliptical mask).
    const auto people = load_identity_folders(root / "orl");
    const std::size_t P = people.size();
    FrontEndParams fp;
    const FrontEnd front_end(fp);
    ClassifierBank bank;
    auto detect_one = [&](const cv::Mat& img) -> cv::Mat {
        const FrontEndResult r = front_end.process(img);
        return r.faces.empty() ? bank.normalize(img, {0, 0, img.cols, img.rows}) : r.faces.front().face.pixels;
    };
    for (const PersonImages& p : people) {
        std::vector<cv::Mat> faces;
        for (int i = 0; i < enrol; ++i) faces.push_back(detect_one(big_face(p, std::size_t(i))));
        bank.add_faces(p.name, faces);
    }
    bank.train();

    // The social graph: circles of 8 people; friends within a circle with probability 0.6,
    // across circles 0.03.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(0, 1);
    const std::size_t circle = 8;
    InMemorySocialGraph graph;
    for (std::size_t a = 0; a < P; ++a) {
        graph.add_person(people[a].name);
        for (std::size_t b = a + 1; b < P; ++b)
            if (uni(rng) < (a / circle == b / circle ? 0.6 : 0.03)) graph.add_friendship(people[a].name, people[b].name);
    }
    // The same graph with people relabelled at random: friendships carry no signal.
    std::vector<std::size_t> perm(P);
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    InMemorySocialGraph shuffled;
    for (const auto& [a, b] : graph.friendships()) {
        auto index = [&](const std::string& n) {
            return std::size_t(std::find_if(people.begin(), people.end(), [&](const PersonImages& p) { return p.name == n; }) -
                               people.begin());
        };
        shuffled.add_friendship(people[perm[index(a)]].name, people[perm[index(b)]].name);
    }

    // Group photos: 3-5 people, mostly from one circle, each with one held-out image.
    Composed set;
    std::uniform_int_distribution<int> size_dist(3, 5);
    std::uniform_int_distribution<std::size_t> person_dist(0, P - 1), image_dist(std::size_t(enrol), 9);
    for (int k = 0; k < photos; ++k) {
        const std::size_t c = person_dist(rng) / circle;
        std::vector<std::size_t> who;
        const int n = size_dist(rng);
        while (int(who.size()) < n) {
            std::size_t p = uni(rng) < 0.85 ? c * circle + person_dist(rng) % circle : person_dist(rng);
            if (p >= P) p = person_dist(rng);
            if (std::find(who.begin(), who.end(), p) == who.end()) who.push_back(p);
        }
        std::vector<cv::Mat> faces;
        for (std::size_t p : who) faces.push_back(big_face(people[p], image_dist(rng)));
        std::vector<cv::Rect> where;
        const cv::Mat canvas = compose(faces, where);
        const FrontEndResult r = front_end.process(canvas);
        set.placed += int(who.size());
        std::vector<std::size_t> truth;
        std::vector<BankScores> scores;
        for (const FrontEndFace& f : r.faces) {
            std::size_t best = who.size();
            double best_iou = 0.4;
            for (std::size_t i = 0; i < where.size(); ++i)
                if (double o = iou(f.detection.box, where[i]); o > best_iou) best_iou = o, best = i;
            if (best == who.size()) continue;  // a false detection: not a face of the photo
            truth.push_back(who[best]);
            scores.push_back(bank.scores(f.face.pixels));
        }
        set.detected += int(truth.size());
        set.people.push_back(truth);
        set.scores.push_back(scores);
    }

    // The first photos are the history: tagged already (true names), they calibrate the friend
    // bonus of each graph. Tagging is measured on the others.
    const std::size_t history = std::size_t(photos) / 4;
    std::vector<std::vector<std::string>> history_names;
    for (std::size_t k = 0; k < history; ++k) {
        history_names.emplace_back();
        for (std::size_t p : set.people[k]) history_names.back().push_back(people[p].name);
    }
    const double lift = friend_lift(history_names, graph), lift_shuffled = friend_lift(history_names, shuffled);
    const double bonus = calibrated_friend_bonus(history_names, graph);
    const double bonus_shuffled = calibrated_friend_bonus(history_names, shuffled);

    // Tagging accuracy of each method.
    auto accuracy = [&](const SocialGraph* g, double bonus, bool unique, std::vector<std::vector<std::string>>* tagged) {
        int ok = 0, total = 0;
        FriendTaggingParams tp;
        tp.friend_bonus = bonus;
        for (std::size_t k = history; k < set.scores.size(); ++k) {
            std::vector<std::string> names;
            if (unique) {
                for (const FaceTag& t : tag_faces(set.scores[k], g, tp)) names.push_back(t.known ? t.name : "");
            } else {
                for (const BankScores& s : set.scores[k]) names.push_back(decide(s.names, s.scores, {}).name);
            }
            for (std::size_t i = 0; i < names.size(); ++i) ok += names[i] == people[set.people[k][i]].name, ++total;
            if (tagged) tagged->push_back(names);
        }
        return total ? double(ok) / total : 0.0;
    };
    std::vector<std::vector<std::string>> tagged_with_friends;
    const double independent = accuracy(nullptr, 0, false, nullptr);
    const double unique_only = accuracy(nullptr, 0, true, nullptr);
    const double with_friends = accuracy(&graph, bonus, true, &tagged_with_friends);
    const double with_shuffled = accuracy(&shuffled, bonus_shuffled, true, nullptr);
    std::vector<JsonObject> sweep;
    for (double b : {0.25, 0.5, 1.0, 2.0}) {
        JsonObject o;
        o.add("friend_bonus", b).add("accuracy", accuracy(&graph, b, true, nullptr)).add("accuracy_shuffled", accuracy(&shuffled, b, true, nullptr));
        sweep.push_back(o);
    }

    // Friendship suggestions from the tagged photos, against a graph with 30% of the friendships
    // hidden: how many suggestions are hidden friendships?
    InMemorySocialGraph known;
    std::vector<std::pair<std::string, std::string>> hidden;
    for (const auto& f : graph.friendships()) {
        if (uni(rng) < 0.3)
            hidden.push_back(f);
        else
            known.add_friendship(f.first, f.second);
    }
    const auto suggestions = suggest_friendships(tagged_with_friends, &known, 3);
    int true_suggestions = 0, top10 = 0;
    for (std::size_t i = 0; i < suggestions.size(); ++i) {
        const bool real = graph.are_friends(suggestions[i].a, suggestions[i].b);
        true_suggestions += real;
        if (i < 10) top10 += real;
    }

    // Tag-to-face on the real group photos of dlib_faces: tags at the hand-drawn boxes' centres
    // plus noise of 15% of the box width.
    FrontEndParams dp;
    dp.use_profile = true;
    dp.normalize = false;
    const FrontEnd dlib_front(dp);
    std::normal_distribution<float> noise(0.f, 0.15f);
    int tags_total = 0, right = 0, wrong = 0, profile = 0, none = 0, taken = 0;
    for (const AnnotatedImage& a : load_dlib_faces(root)) {
        const cv::Mat img = load_image(a.file);
        std::vector<Detection> det;
        for (const FrontEndFace& f : dlib_front.process(img).faces) det.push_back(f.detection);
        std::vector<PhotoTag> tags;
        for (std::size_t i = 0; i < a.faces.size(); ++i) {
            const cv::Rect& b = a.faces[i];
            cv::Point2f pt(b.x + b.width / 2.f + noise(rng) * b.width, b.y + b.height / 2.f + noise(rng) * b.width);
            pt.x = std::clamp(pt.x, 0.f, float(img.cols - 1));
            pt.y = std::clamp(pt.y, 0.f, float(img.rows - 1));
            tags.push_back({"person" + std::to_string(i), pt});
        }
        const auto res = resolve_tags(det, tags, img.size());
        for (std::size_t i = 0; i < res.size(); ++i) {
            ++tags_total;
            switch (res[i].outcome) {
            case TagOutcome::Resolved:
                (iou(det[std::size_t(res[i].face)].box, a.faces[i]) >= 0.5 ? right : wrong)++;
                break;
            case TagOutcome::NearestIsProfile: ++profile; break;
            case TagOutcome::NoFaceNearby: ++none; break;
            case TagOutcome::FaceTaken: ++taken; break;
            }
        }
    }

    JsonObject result;
    result.add("people", P).add("photos", photos).add("seed", long(seed)).add("enrol_per_person", enrol);
    result.add("friendships", graph.friendships().size()).add("faces_placed", set.placed).add("faces_detected", set.detected);
    result.add("accuracy_independent", independent).add("accuracy_one_person_per_face", unique_only);
    result.add("history_photos", history).add("lift", lift).add("lift_shuffled", lift_shuffled);
    result.add("friend_bonus", bonus).add("friend_bonus_shuffled", bonus_shuffled);
    result.add("accuracy_friend_prior", with_friends).add("accuracy_shuffled_graph", with_shuffled).add("bonus_sweep", sweep);
    // Chance level: the share of hidden friendships among all pairs not known as friends.
    const double pairs = double(P * (P - 1) / 2) - double(known.friendships().size());
    const double base_rate = pairs > 0 ? double(hidden.size()) / pairs : 0.0;
    result.add("hidden_friendships", hidden.size()).add("suggestions", suggestions.size()).add("suggestion_base_rate", base_rate);
    result.add("suggestion_precision", suggestions.empty() ? 0.0 : double(true_suggestions) / suggestions.size());
    result.add("suggestion_precision_top10", std::min<std::size_t>(10, suggestions.size()) ? double(top10) / std::min<std::size_t>(10, suggestions.size()) : 0.0);
    result.add("suggestion_recall", hidden.empty() ? 0.0 : double(true_suggestions) / hidden.size());
    JsonObject dl;
    dl.add("tags", tags_total).add("right_face", right).add("wrong_face", wrong).add("refused_profile", profile);
    dl.add("no_face_nearby", none).add("face_taken", taken);
    result.add("dlib_tag_to_face", dl);
    if (json_out) {
        std::cout << result.str() << "\n";
        return 0;
    }
    std::cout << std::fixed << std::setprecision(3) << "composed photos: " << photos << " (" << history
              << " as tagged history, " << set.detected << " of " << set.placed << " faces detected), 40 ORL people enrolled from " << enrol << " image(s), " << graph.friendships().size()
              << " friendships (seed " << seed << ")\n"
              << "  recognition alone, each face on its own   " << independent << "\n"
              << "  one person per face, no friend prior      " << unique_only << "\n"
              << "  friend prior (lift " << lift << ", bonus " << bonus << ")   " << with_friends << "\n"
              << "  shuffled graph (lift " << lift_shuffled << ", bonus " << bonus_shuffled << ")   " << with_shuffled << "\n"
              << "friendship suggestions (pairs in >= 3 photos; 30% of " << graph.friendships().size()
              << " friendships hidden): " << suggestions.size() << " suggested, precision " << (suggestions.empty() ? 0.0 : double(true_suggestions) / suggestions.size())
              << " (top 10: " << (suggestions.empty() ? 0.0 : double(top10) / std::min<std::size_t>(10, suggestions.size()))
              << "), recall " << (hidden.empty() ? 0.0 : double(true_suggestions) / hidden.size()) << "; chance "
              << base_rate << "\n"
              << "dlib_faces tags (box centre + 15% noise): " << right << " of " << tags_total << " to the right face, " << wrong
              << " wrong, " << profile << " refused (profile), " << none << " no face nearby, " << taken << " face taken\n";
    return 0;
}

}  // namespace facesocial::cli
