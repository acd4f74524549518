// Friend-biased tagging of group photos and its inverse (paper section VI).
//
// Tagging: every face of a photo has been scored against the bank. The most confident face is
// fixed first; the remaining faces' hypotheses are then biased towards the fixed people's
// friends (with two fixed people: mutual friends get the most, friends of one less, others
// nothing), the next most confident face is fixed, and so on face by face. One person per face,
// and no person twice in a photo.
//
// Suggestions: people who appear together in several photos but are not yet friends become
// ranked friendship suggestions.
#pragma once

#include <string>
#include <vector>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/decision.hpp"
#include "facesocial/social_graph.hpp"

namespace facesocial {

struct FriendTaggingParams {
    /// Added to a candidate's score for every already fixed person of the photo who is their
    /// friend (the scores are the EHMM's per-observation log-likelihoods, whose winning
    /// margins are typically 0.2-1.5). 0 = recognition alone (still one person per face).
    double friend_bonus = 0.5;
    /// Applied to each face's biased scores; an unknown face is left untagged and does not
    /// bias the others.
    UnknownRule unknown;
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// The tag given to one face.
struct FaceTag {
    bool known = false;      ///< false: unknown under the rule, or no candidate left
    std::string name;        ///< the person, when known
    double score = 0;        ///< raw (unbiased) score of that person for this face
    double bonus = 0;        ///< friend bonus that person received
    double margin = 0;       ///< biased margin over the runner-up when the face was fixed
    int order = -1;          ///< 0 for the face fixed first, 1 next, ...
};

/// Tags the faces of one photo. faces[i] = the bank scores of face i (names may differ in order
/// between faces; a person missing from a face's scores cannot be that face). `graph` may be
/// null (no bias). `present` = people known to be in the photo already (for example from its
/// tags): they are fixed from the start, bias the others and are not given to any face.
/// Throws std::invalid_argument for malformed scores or invalid params.
std::vector<FaceTag> tag_faces(const std::vector<BankScores>& faces, const SocialGraph* graph,
                               const FriendTaggingParams& params = {}, const std::vector<std::string>& present = {});

/// How much more often friends appear together than people picked at random: P(friends |
/// seen together) / P(friends), over the pairs of people in already tagged `photos` (1 = the
/// graph says nothing about who appears with whom; 0 when no pair was seen together).
double friend_lift(const std::vector<std::vector<std::string>>& photos, const SocialGraph& graph);

/// A friend bonus backed by evidence: `scale` x ln(lift), never negative. A graph that carries
/// no signal about who appears together (lift about 1) gets a bonus about 0, so the prior
/// cannot hurt; a graph whose friends do appear together gets a bonus growing with the lift.
/// Throws std::invalid_argument for scale < 0.
double calibrated_friend_bonus(const std::vector<std::vector<std::string>>& photos, const SocialGraph& graph,
                               double scale = 0.1);

/// One suggested friendship.
struct FriendSuggestion {
    std::string a, b;  ///< a < b
    int photos = 0;    ///< photos they appear in together
};

/// People seen together in at least `min_photos` photos and not yet friends in `graph` (may be
/// null), most photos first (ties by names). photos[k] = the people in photo k (a name repeated
/// within one photo counts once).
std::vector<FriendSuggestion> suggest_friendships(const std::vector<std::vector<std::string>>& photos,
                                                  const SocialGraph* graph, int min_photos = 2);

}  // namespace facesocial
