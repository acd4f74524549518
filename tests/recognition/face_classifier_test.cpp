#include <gtest/gtest.h>

#include "facesocial/datasets.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

/// ORL canonical split: images 1-5 train, 6-10 test, for every person.
struct OrlSplit {
    std::vector<std::vector<cv::Mat>> train, test;
};

const OrlSplit& orl() {
    static const OrlSplit split = [] {
        OrlSplit s;
        for (const auto& person : load_cropped_faces(test::data() / "orl").faces) {
            s.train.emplace_back(person.begin(), person.begin() + 5);
            s.test.emplace_back(person.begin() + 5, person.end());
        }
        return s;
    }();
    return split;
}

double accuracy(FaceClassifier& c) {
    c.train(orl().train);
    int ok = 0, n = 0;
    for (std::size_t p = 0; p < orl().test.size(); ++p)
        for (const cv::Mat& f : orl().test[p]) {
            const auto s = c.scores(f);
            EXPECT_EQ(s.size(), orl().train.size());
            ok += std::size_t(std::max_element(s.begin(), s.end()) - s.begin()) == p;
            ++n;
        }
    return double(ok) / n;
}

}  // namespace

TEST(FaceClassifier, EhmmGuardsOrlCanonicalAccuracy) {
    auto c = FaceClassifier::create();
    EXPECT_EQ(c->name(), "ehmm");
    EXPECT_GE(accuracy(*c), 0.97);
}

TEST(FaceClassifier, OpencvAdaptersWorkSideBySide) {
    for (ClassifierKind k : {ClassifierKind::Eigenfaces, ClassifierKind::Fisherfaces, ClassifierKind::Lbph}) {
        ClassifierParams p;
        p.kind = k;
        auto c = FaceClassifier::create(p);
        EXPECT_EQ(c->name(), to_string(k));
        EXPECT_GE(accuracy(*c), 0.8) << to_string(k);
        EXPECT_EQ(c->size(), 40u);
    }
}

TEST(FaceClassifier, ErrorsBeforeTrainingAndForBadFaces) {
    auto c = FaceClassifier::create();
    EXPECT_THROW(c->scores(orl().test[0][0]), std::logic_error);
    EXPECT_THROW(c->train({}), std::invalid_argument);
    EXPECT_THROW(c->train({{}}), std::invalid_argument);
    EXPECT_THROW(c->train({{cv::Mat(112, 92, CV_8UC3)}}), std::invalid_argument);
    ClassifierParams p;
    p.kind = ClassifierKind::Fisherfaces;
    EXPECT_THROW(FaceClassifier::create(p)->train({orl().train[0]}), std::invalid_argument);
    EXPECT_THROW(classifier_kind_from_string("svm"), std::invalid_argument);
    EXPECT_EQ(classifier_kind_from_string("lbph"), ClassifierKind::Lbph);
}
