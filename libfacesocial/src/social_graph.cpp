#include "facesocial/social_graph.hpp"

#include <stdexcept>

namespace facesocial {

void InMemorySocialGraph::add_person(const std::string& person) {
    if (person.empty()) throw std::invalid_argument("InMemorySocialGraph: expected a person's name, got an empty one");
    friends_[person];
}

void InMemorySocialGraph::add_friendship(const std::string& a, const std::string& b) {
    if (a.empty() || b.empty())
        throw std::invalid_argument("InMemorySocialGraph::add_friendship: expected two names, got an empty one");
    if (a == b)
        throw std::invalid_argument("InMemorySocialGraph::add_friendship: expected two different people, got '" + a +
                                    "' twice");
    friends_[a].insert(b);
    friends_[b].insert(a);
}

void InMemorySocialGraph::remove_friendship(const std::string& a, const std::string& b) {
    if (auto it = friends_.find(a); it != friends_.end()) it->second.erase(b);
    if (auto it = friends_.find(b); it != friends_.end()) it->second.erase(a);
}

bool InMemorySocialGraph::are_friends(const std::string& a, const std::string& b) const {
    const auto it = friends_.find(a);
    return it != friends_.end() && it->second.count(b) > 0;
}

std::vector<std::string> InMemorySocialGraph::friends_of(const std::string& person) const {
    const auto it = friends_.find(person);
    if (it == friends_.end()) return {};
    return {it->second.begin(), it->second.end()};
}

std::vector<std::string> InMemorySocialGraph::people() const {
    std::vector<std::string> out;
    for (const auto& [p, f] : friends_) out.push_back(p);
    return out;
}

std::vector<std::pair<std::string, std::string>> InMemorySocialGraph::friendships() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& [p, fs] : friends_)
        for (const std::string& f : fs)
            if (p < f) out.emplace_back(p, f);
    return out;
}

}  // namespace facesocial
