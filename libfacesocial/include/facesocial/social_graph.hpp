// The social network as the vision module sees it (paper section VI): who is friends with whom.
// An interface, so the robot's database (or a social network's API) can stand behind it; the
// library ships a plain in-memory graph.
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace facesocial {

/// Undirected friendships between named people. Implementations must be safe to read from
/// several threads.
class SocialGraph {
public:
    virtual ~SocialGraph() = default;
    /// True when a and b are friends (false for a == b or unknown people).
    virtual bool are_friends(const std::string& a, const std::string& b) const = 0;
    /// The friends of `person` (empty for an unknown person), sorted.
    virtual std::vector<std::string> friends_of(const std::string& person) const = 0;
};

/// A SocialGraph held in memory.
class InMemorySocialGraph : public SocialGraph {
public:
    /// Adds the friendship a - b (both people are created as needed). std::invalid_argument
    /// for an empty name or a == b.
    void add_friendship(const std::string& a, const std::string& b);
    /// Removes it if present.
    void remove_friendship(const std::string& a, const std::string& b);
    /// Adds a person without friends (nothing when already there).
    void add_person(const std::string& person);

    bool are_friends(const std::string& a, const std::string& b) const override;
    std::vector<std::string> friends_of(const std::string& person) const override;
    bool contains(const std::string& person) const { return friends_.count(person) > 0; }
    /// Everyone, sorted.
    std::vector<std::string> people() const;
    /// Every friendship once, as (smaller name, larger name), sorted.
    std::vector<std::pair<std::string, std::string>> friendships() const;

private:
    std::map<std::string, std::set<std::string>> friends_;
};

}  // namespace facesocial
