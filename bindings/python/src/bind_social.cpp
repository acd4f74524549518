// Social photos: the social graph, tags to faces, friend-biased tagging and suggestions,
// training samples with provenance, selection policies and background retraining.
#include "common.hpp"
#include "facesocial/background_trainer.hpp"
#include "facesocial/friend_tagging.hpp"
#include "facesocial/photo_tags.hpp"
#include "facesocial/social_graph.hpp"
#include "facesocial/training_set.hpp"

namespace facesocial::python {

void bind_social(py::module_& m) {
    py::class_<SocialGraph, std::shared_ptr<SocialGraph>>(m, "SocialGraph", "Who is friends with whom (interface).")
        .def("are_friends", &SocialGraph::are_friends, py::arg("a"), py::arg("b"))
        .def("friends_of", &SocialGraph::friends_of, py::arg("person"));
    py::class_<InMemorySocialGraph, SocialGraph, std::shared_ptr<InMemorySocialGraph>>(m, "InMemorySocialGraph")
        .def(py::init<>())
        .def(py::init([](const std::vector<std::pair<std::string, std::string>>& friendships) {
                 auto g = std::make_shared<InMemorySocialGraph>();
                 for (const auto& [a, b] : friendships) g->add_friendship(a, b);
                 return g;
             }),
             py::arg("friendships"), "From a list of (a, b) pairs.")
        .def("add_friendship", &InMemorySocialGraph::add_friendship, py::arg("a"), py::arg("b"))
        .def("remove_friendship", &InMemorySocialGraph::remove_friendship, py::arg("a"), py::arg("b"))
        .def("add_person", &InMemorySocialGraph::add_person, py::arg("person"))
        .def("__contains__", &InMemorySocialGraph::contains)
        .def_property_readonly("people", &InMemorySocialGraph::people)
        .def_property_readonly("friendships", &InMemorySocialGraph::friendships)
        .def("__repr__", [](const InMemorySocialGraph& g) {
            return "InMemorySocialGraph(" + std::to_string(g.people().size()) + " people, " +
                   std::to_string(g.friendships().size()) + " friendships)";
        });

    // --- tags ----------------------------------------------------------------------------------
    py::class_<PhotoTag>(m, "PhotoTag", "A person and a rough point on the photo.")
        .def(py::init([](std::string person, const py::tuple& point) {
                 if (point.size() != 2) throw std::invalid_argument("PhotoTag: expected a point (x, y)");
                 return PhotoTag{std::move(person), {point[0].cast<float>(), point[1].cast<float>()}};
             }),
             py::arg("person"), py::arg("point"))
        .def_readwrite("person", &PhotoTag::person)
        .def_property_readonly("point", [](const PhotoTag& t) { return py::make_tuple(t.point.x, t.point.y); })
        .def("__repr__", [](const PhotoTag& t) {
            return "PhotoTag('" + t.person + "', (" + std::to_string(t.point.x) + ", " + std::to_string(t.point.y) + "))";
        });
    py::enum_<TagOutcome>(m, "TagOutcome")
        .value("RESOLVED", TagOutcome::Resolved)
        .value("NEAREST_IS_PROFILE", TagOutcome::NearestIsProfile)
        .value("NO_FACE_NEARBY", TagOutcome::NoFaceNearby)
        .value("FACE_TAKEN", TagOutcome::FaceTaken);
    py::class_<TagResolution>(m, "TagResolution", "What became of a tag.")
        .def_readonly("tag", &TagResolution::tag)
        .def_readonly("outcome", &TagResolution::outcome)
        .def_readonly("face", &TagResolution::face, "index of the nearest detection (-1 when none)")
        .def_readonly("distance", &TagResolution::distance, "in face widths")
        .def_readonly("reason", &TagResolution::reason)
        .def("__repr__", [](const TagResolution& r) {
            return "TagResolution('" + r.tag.person + "', " + to_string(r.outcome) + ", face=" + std::to_string(r.face) + ")";
        });
    ParamsClass<TagResolverParams>(m, "TagResolverParams", "Parameters of resolve_tags.")
        .field("max_distance", &TagResolverParams::max_distance, "farthest tag from a face centre, in face widths")
        .done();
    m.def(
        "resolve_tags",
        [](const std::vector<Detection>& faces, const std::vector<PhotoTag>& tags, const py::tuple& image_size,
           const TagResolverParams& params, const std::vector<std::string>& known) {
            return resolve_tags(faces, tags, size_from_tuple(image_size, "resolve_tags"), params, known);
        },
        py::arg("faces"), py::arg("tags"), py::arg("image_size"), py::arg("params") = TagResolverParams{},
        py::arg("known_people") = std::vector<std::string>{},
        "Each tag to the nearest detected face of a (width, height) photo; a profile nearest face refuses the tag.");

    // --- friend-biased tagging -----------------------------------------------------------------
    ParamsClass<FriendTaggingParams>(m, "FriendTaggingParams", "Parameters of tag_faces.")
        .field("friend_bonus", &FriendTaggingParams::friend_bonus, "score bonus per tagged friend")
        .field("unknown", &FriendTaggingParams::unknown, "unknown rule on the biased scores")
        .done();
    py::class_<FaceTag>(m, "FaceTag", "The tag given to one face.")
        .def_readonly("known", &FaceTag::known)
        .def_readonly("name", &FaceTag::name)
        .def_readonly("score", &FaceTag::score, "raw score of that person")
        .def_readonly("bonus", &FaceTag::bonus, "friend bonus that person received")
        .def_readonly("margin", &FaceTag::margin)
        .def_readonly("order", &FaceTag::order, "0 for the face fixed first")
        .def("__repr__", [](const FaceTag& t) {
            return "FaceTag(" + (t.known ? "'" + t.name + "'" : std::string("unknown")) + ", order=" + std::to_string(t.order) + ")";
        });
    m.def(
        "tag_faces",
        [](const std::vector<BankScores>& faces, const std::shared_ptr<SocialGraph>& graph, const FriendTaggingParams& params,
           const std::vector<std::string>& present) {
            py::gil_scoped_release release;
            return tag_faces(faces, graph.get(), params, present);
        },
        py::arg("faces"), py::arg("graph") = nullptr, py::arg("params") = FriendTaggingParams{},
        py::arg("present") = std::vector<std::string>{},
        "Names the faces of a group photo, most confident first, biased towards the friends of those already named.");
    py::class_<FriendSuggestion>(m, "FriendSuggestion")
        .def_readonly("a", &FriendSuggestion::a)
        .def_readonly("b", &FriendSuggestion::b)
        .def_readonly("photos", &FriendSuggestion::photos)
        .def("__repr__", [](const FriendSuggestion& s) {
            return "FriendSuggestion('" + s.a + "', '" + s.b + "', photos=" + std::to_string(s.photos) + ")";
        });
    m.def(
        "suggest_friendships",
        [](const std::vector<std::vector<std::string>>& photos, const std::shared_ptr<SocialGraph>& graph, int min_photos) {
            return suggest_friendships(photos, graph.get(), min_photos);
        },
        py::arg("photos"), py::arg("graph") = nullptr, py::arg("min_photos") = 2);
    m.def("friend_lift", &friend_lift, py::arg("photos"), py::arg("graph"));
    m.def("calibrated_friend_bonus", &calibrated_friend_bonus, py::arg("photos"), py::arg("graph"), py::arg("scale") = 0.3);

    // --- background retraining (training sets and policies: bind_recognition.cpp) ----------------
    ParamsClass<BackgroundTrainerParams>(m, "BackgroundTrainerParams", "Parameters of the background trainer.")
        .field("nice", &BackgroundTrainerParams::nice, "niceness of the trainer thread, 0-19")
        .done();
    py::class_<BackgroundTrainer>(m, "BackgroundTrainer", "Retrains queued people on one low-priority thread.")
        .def(py::init<std::shared_ptr<ClassifierBank>, const BackgroundTrainerParams&>(), py::arg("bank"),
             py::arg("params") = BackgroundTrainerParams{})
        .def("request", &BackgroundTrainer::request, py::arg("name"))
        .def("wait_idle", &BackgroundTrainer::wait_idle, py::call_guard<py::gil_scoped_release>())
        .def_property_readonly("pending", &BackgroundTrainer::pending)
        .def_property_readonly("trained", &BackgroundTrainer::trained)
        .def_property_readonly("errors", &BackgroundTrainer::errors);
}

}  // namespace facesocial::python
