// Friend-biased tagging and friendship suggestions: the three-level bias, one person per face,
// the prior correcting a real misrecognised ORL face, co-occurrence suggestions, bad inputs.
#include <gtest/gtest.h>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/friend_tagging.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

TEST(SocialGraph, FriendshipsAreUndirectedAndValidated) {
    InMemorySocialGraph g;
    g.add_friendship("ann", "bob");
    g.add_friendship("cy", "ann");
    g.add_person("dan");
    EXPECT_TRUE(g.are_friends("bob", "ann"));
    EXPECT_FALSE(g.are_friends("bob", "cy"));
    EXPECT_FALSE(g.are_friends("ann", "ann"));
    EXPECT_EQ(g.friends_of("ann"), (std::vector<std::string>{"bob", "cy"}));
    EXPECT_TRUE(g.friends_of("zed").empty());
    EXPECT_EQ(g.people().size(), 4u);
    EXPECT_EQ(g.friendships().size(), 2u);
    g.remove_friendship("bob", "ann");
    EXPECT_FALSE(g.are_friends("ann", "bob"));
    EXPECT_THROW(g.add_friendship("ann", "ann"), std::invalid_argument);
    EXPECT_THROW(g.add_friendship("", "ann"), std::invalid_argument);
}

TEST(FriendTagging, ThreeLevelsOfBiasWithTwoFixedPeople) {
    // Faces 0 and 1 are sure (ann, bob). Face 2 is torn between cy, dan and eve: raw scores
    // eve > dan > cy by 0.3 each. cy is a friend of both, dan of one, eve of none.
    const std::vector<std::string> names{"ann", "bob", "cy", "dan", "eve"};
    std::vector<BankScores> faces{{names, {-10, -15, -15, -15, -15}},
                                  {names, {-15, -10.5, -15, -15, -15}},
                                  {names, {-14, -14, -12.6, -12.3, -12.0}}};
    InMemorySocialGraph g;
    g.add_friendship("cy", "ann");
    g.add_friendship("cy", "bob");
    g.add_friendship("dan", "ann");
    FriendTaggingParams p;
    p.friend_bonus = 0.5;
    const auto tags = tag_faces(faces, &g, p);
    EXPECT_EQ(tags[0].name, "ann");
    EXPECT_EQ(tags[0].order, 0);
    EXPECT_EQ(tags[1].name, "bob");
    EXPECT_EQ(tags[1].order, 1);
    // cy: -12.6 + 2 x 0.5 = -11.6; dan: -12.3 + 0.5 = -11.8; eve: -12.0.
    EXPECT_EQ(tags[2].name, "cy");
    EXPECT_DOUBLE_EQ(tags[2].bonus, 1.0);
    EXPECT_DOUBLE_EQ(tags[2].score, -12.6);
    EXPECT_NEAR(tags[2].margin, 0.2, 1e-12);
    // Without the graph, or with bonus 0, recognition alone picks eve.
    EXPECT_EQ(tag_faces(faces, nullptr, p)[2].name, "eve");
    p.friend_bonus = 0;
    EXPECT_EQ(tag_faces(faces, &g, p)[2].name, "eve");
    // A bonus between the two gaps separates the levels: 0.25 lifts cy to -12.1 and dan to -12.05.
    p.friend_bonus = 0.25;
    EXPECT_EQ(tag_faces(faces, &g, p)[2].name, "eve");
}

TEST(FriendTagging, OnePersonPerFaceAndNoPersonTwice) {
    const std::vector<std::string> names{"ann", "bob", "cy"};
    // Both faces prefer ann; face 1 more surely, so face 0 gets its next best.
    std::vector<BankScores> faces{{names, {-10, -10.2, -13}}, {names, {-10, -12, -13}}};
    const auto tags = tag_faces(faces, nullptr);
    EXPECT_EQ(tags[1].name, "ann");
    EXPECT_EQ(tags[0].name, "bob");
    // More faces than people: the last face has no candidate left and stays unknown.
    faces.push_back({names, {-10, -10, -10}});
    faces.push_back({names, {-11, -11, -9}});
    const auto more = tag_faces(faces, nullptr);
    std::set<std::string> used;
    int unknown = 0;
    for (const FaceTag& t : more) {
        if (t.known)
            EXPECT_TRUE(used.insert(t.name).second) << t.name << " twice";
        else
            ++unknown;
    }
    EXPECT_EQ(unknown, 1);
}

TEST(FriendTagging, UnknownFacesAreLeftUntagged) {
    const std::vector<std::string> names{"ann", "bob", "cy"};
    FriendTaggingParams p;
    p.unknown.min_margin = 1.0;
    // Face 1 is surely ann; then face 0 is torn between bob and cy (margin 0.1 < 1).
    const auto tags = tag_faces({{names, {-10, -10.5, -10.6}}, {names, {-10, -14, -14}}}, nullptr, p);
    EXPECT_TRUE(tags[1].known);
    EXPECT_EQ(tags[1].name, "ann");
    EXPECT_FALSE(tags[0].known);
    EXPECT_TRUE(tags[0].name.empty());
}

TEST(FriendTagging, FriendPriorCorrectsARealMisrecognisedFace) {
    // ORL bank from two images per person; find a held-out face whose true person comes second.
    const FaceSet orl = load_cropped_faces(test::data() / "orl");
    ClassifierBankParams bp;
    bp.normalizer = NormalizerParams::cropped();
    ClassifierBank bank(bp);
    for (std::size_t p = 0; p < orl.names.size(); ++p) bank.add_faces(orl.names[p], {orl.faces[p][0], orl.faces[p][1]});
    bank.train();
    for (std::size_t p = 0; p < orl.names.size(); ++p)
        for (std::size_t i = 2; i < 10; ++i) {
            const BankScores s = bank.scores(orl.faces[p][i]);
            const auto ranked = rank_candidates(s.names, s.scores);
            if (ranked[1].name != orl.names[p] || ranked[0].score - ranked[1].score > 0.4) continue;
            // A group photo: two people recognised with confidence, and the misrecognised face.
            std::vector<BankScores> faces;
            std::vector<std::string> truth;
            for (std::size_t q = 0; q < orl.names.size() && faces.size() < 2; ++q) {
                if (q == p || orl.names[q] == ranked[0].name) continue;
                const BankScores sq = bank.scores(orl.faces[q][9]);
                const Decision d = decide(sq.names, sq.scores, {});
                if (d.name == orl.names[q] && d.margin > 1.0) faces.push_back(sq), truth.push_back(orl.names[q]);
            }
            ASSERT_EQ(faces.size(), 2u);
            faces.push_back(s);
            EXPECT_EQ(tag_faces(faces, nullptr)[2].name, ranked[0].name);  // recognition alone: wrong
            InMemorySocialGraph g;
            g.add_friendship(orl.names[p], truth[0]);
            g.add_friendship(orl.names[p], truth[1]);
            const auto tags = tag_faces(faces, &g);
            EXPECT_EQ(tags[0].name, truth[0]);
            EXPECT_EQ(tags[1].name, truth[1]);
            EXPECT_EQ(tags[2].name, orl.names[p]);  // mutual friend of both: corrected
            EXPECT_EQ(tags[2].order, 2);
            return;
        }
    FAIL() << "no held-out ORL face with its person ranked second within 0.4";
}

TEST(FriendSuggestions, PeopleSeenTogetherBecomeRankedSuggestions) {
    InMemorySocialGraph g;
    g.add_friendship("ann", "bob");
    const std::vector<std::vector<std::string>> photos{
        {"ann", "bob", "cy"}, {"ann", "cy"}, {"cy", "ann", "dan"}, {"bob", "dan"}, {"bob", "dan", "dan"}, {"eve"}};
    const auto s = suggest_friendships(photos, &g, 2);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].a, "ann");
    EXPECT_EQ(s[0].b, "cy");
    EXPECT_EQ(s[0].photos, 3);
    EXPECT_EQ(s[1].a, "bob");
    EXPECT_EQ(s[1].b, "dan");
    EXPECT_EQ(s[1].photos, 2);  // "dan" twice in one photo counts once
    EXPECT_EQ(suggest_friendships(photos, nullptr, 1).size(), 6u);  // every pair seen together once
    EXPECT_EQ(suggest_friendships(photos, &g, 1).size(), 5u);       // ... but ann-bob, friends already
    EXPECT_THROW(suggest_friendships(photos, nullptr, 0), std::invalid_argument);
}

TEST(FriendTagging, BadInputsGiveClearErrors) {
    EXPECT_THROW(tag_faces({{{"ann"}, {-1, -2}}}, nullptr), std::invalid_argument);
    EXPECT_THROW(tag_faces({{{"ann"}, {NAN}}}, nullptr), std::invalid_argument);
    FriendTaggingParams p;
    p.friend_bonus = -1;
    EXPECT_THROW(tag_faces({}, nullptr, p), std::invalid_argument);
    EXPECT_TRUE(tag_faces({}, nullptr).empty());
}

TEST(FriendTagging, PeopleKnownFromTagsBiasTheRestAndAreNotReused) {
    const std::vector<std::string> names{"ann", "bob", "cy"};
    InMemorySocialGraph g;
    g.add_friendship("ann", "cy");
    // One untagged face; ann is tagged elsewhere in the photo. bob leads cy by 0.2 raw.
    const auto tags = tag_faces({{names, {-9, -12.0, -12.2}}}, &g, {}, {"ann"});
    EXPECT_EQ(tags[0].name, "cy");
    EXPECT_DOUBLE_EQ(tags[0].bonus, 0.5);
}
