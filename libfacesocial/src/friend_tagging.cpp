#include "facesocial/friend_tagging.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace facesocial {

void FriendTaggingParams::validate() const {
    if (!(friend_bonus >= 0 && friend_bonus <= 1000))
        throw std::invalid_argument("FriendTaggingParams: expected friend_bonus in [0, 1000], got " +
                                    std::to_string(friend_bonus));
    unknown.validate();
}

std::vector<FaceTag> tag_faces(const std::vector<BankScores>& faces, const SocialGraph* graph,
                               const FriendTaggingParams& params, const std::vector<std::string>& present) {
    params.validate();
    for (std::size_t i = 0; i < faces.size(); ++i) {
        if (faces[i].names.size() != faces[i].scores.size())
            throw std::invalid_argument("tag_faces: expected as many scores as names for face " + std::to_string(i));
        for (double s : faces[i].scores)
            if (!std::isfinite(s)) throw std::invalid_argument("tag_faces: expected finite scores for face " + std::to_string(i));
    }
    std::vector<FaceTag> out(faces.size());
    std::vector<std::string> fixed = present;  // people already tagged in this photo
    std::set<std::size_t> open;
    for (std::size_t i = 0; i < faces.size(); ++i) open.insert(i);
    int order = 0;
    while (!open.empty()) {
        // For every open face: biased scores of the people not yet used, and its decision.
        std::size_t best_face = *open.begin();
        Decision best;
        double best_margin = -std::numeric_limits<double>::infinity();
        std::vector<double> best_bonus;
        std::vector<std::string> best_names;
        std::vector<double> best_raw;
        for (std::size_t i : open) {
            std::vector<std::string> names;
            std::vector<double> biased, raw, bonus;
            for (std::size_t k = 0; k < faces[i].names.size(); ++k) {
                const std::string& who = faces[i].names[k];
                if (std::find(fixed.begin(), fixed.end(), who) != fixed.end()) continue;
                double b = 0;
                if (graph)
                    for (const std::string& f : fixed)
                        if (graph->are_friends(who, f)) b += params.friend_bonus;
                names.push_back(who);
                raw.push_back(faces[i].scores[k]);
                bonus.push_back(b);
                biased.push_back(faces[i].scores[k] + b);
            }
            const Decision d = decide(names, biased, params.unknown);
            // Confidence: the margin of the biased scores (one candidate left: infinite).
            const double margin = names.empty() ? -std::numeric_limits<double>::infinity() : d.margin;
            if (margin > best_margin || (margin == best_margin && i < best_face)) {
                best_margin = margin, best_face = i, best = d, best_names = names, best_raw = raw, best_bonus = bonus;
            }
        }
        FaceTag& t = out[best_face];
        t.order = order++;
        t.margin = best_margin;
        if (best.known && !best_names.empty()) {
            const std::size_t k = std::size_t(std::find(best_names.begin(), best_names.end(), best.name) - best_names.begin());
            t.known = true;
            t.name = best.name;
            t.score = best_raw[k];
            t.bonus = best_bonus[k];
            fixed.push_back(best.name);
        }
        open.erase(best_face);
    }
    return out;
}

double friend_lift(const std::vector<std::vector<std::string>>& photos, const SocialGraph& graph) {
    std::set<std::string> everyone;
    std::set<std::pair<std::string, std::string>> together;
    for (const auto& photo : photos) {
        const std::set<std::string> people(photo.begin(), photo.end());
        for (auto a = people.begin(); a != people.end(); ++a) {
            if (a->empty()) continue;
            everyone.insert(*a);
            for (auto b = std::next(a); b != people.end(); ++b)
                if (!b->empty()) together.insert({*a, *b});
        }
    }
    if (together.empty()) return 0;
    double friends_together = 0, friends_all = 0, pairs_all = 0;
    for (const auto& [a, b] : together) friends_together += graph.are_friends(a, b);
    for (auto a = everyone.begin(); a != everyone.end(); ++a)
        for (auto b = std::next(a); b != everyone.end(); ++b) friends_all += graph.are_friends(*a, *b), ++pairs_all;
    if (friends_all == 0) return 1;
    return (friends_together / double(together.size())) / (friends_all / pairs_all);
}

double calibrated_friend_bonus(const std::vector<std::vector<std::string>>& photos, const SocialGraph& graph, double scale) {
    if (!(scale >= 0)) throw std::invalid_argument("calibrated_friend_bonus: expected scale >= 0, got " + std::to_string(scale));
    const double lift = friend_lift(photos, graph);
    return lift > 1 ? scale * std::log(lift) : 0.0;
}

std::vector<FriendSuggestion> suggest_friendships(const std::vector<std::vector<std::string>>& photos,
                                                  const SocialGraph* graph, int min_photos) {
    if (min_photos < 1)
        throw std::invalid_argument("suggest_friendships: expected min_photos >= 1, got " + std::to_string(min_photos));
    std::map<std::pair<std::string, std::string>, int> together;
    for (const auto& photo : photos) {
        const std::set<std::string> people(photo.begin(), photo.end());
        for (auto a = people.begin(); a != people.end(); ++a)
            for (auto b = std::next(a); b != people.end(); ++b)
                if (!a->empty() && !b->empty()) ++together[{*a, *b}];
    }
    std::vector<FriendSuggestion> out;
    for (const auto& [pair, n] : together)
        if (n >= min_photos && !(graph && graph->are_friends(pair.first, pair.second)))
            out.push_back({pair.first, pair.second, n});
    std::stable_sort(out.begin(), out.end(), [](const FriendSuggestion& x, const FriendSuggestion& y) { return x.photos > y.photos; });
    return out;
}

}  // namespace facesocial
