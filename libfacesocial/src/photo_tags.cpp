#include "facesocial/photo_tags.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace facesocial {

std::string to_string(TagOutcome outcome) {
    switch (outcome) {
    case TagOutcome::Resolved: return "resolved";
    case TagOutcome::NearestIsProfile: return "nearest_is_profile";
    case TagOutcome::NoFaceNearby: return "no_face_nearby";
    case TagOutcome::FaceTaken: return "face_taken";
    }
    return "?";
}

void TagResolverParams::validate() const {
    if (!(max_distance > 0 && max_distance <= 100))
        throw std::invalid_argument("TagResolverParams: expected max_distance in (0, 100], got " + std::to_string(max_distance));
}

std::vector<TagResolution> resolve_tags(const std::vector<Detection>& faces, const std::vector<PhotoTag>& tags,
                                        cv::Size image_size, const TagResolverParams& params,
                                        const std::vector<std::string>& known_people) {
    params.validate();
    std::set<std::string> seen;
    for (const PhotoTag& t : tags) {
        if (t.person.empty()) throw std::invalid_argument("resolve_tags: expected a person for every tag, got an empty name");
        if (!seen.insert(t.person).second)
            throw std::invalid_argument("resolve_tags: expected each person tagged once per photo, got '" + t.person + "' twice");
        if (!(t.point.x >= 0 && t.point.y >= 0 && t.point.x < image_size.width && t.point.y < image_size.height))
            throw std::invalid_argument("resolve_tags: expected the tag of '" + t.person + "' inside the " +
                                        std::to_string(image_size.width) + "x" + std::to_string(image_size.height) +
                                        " photo, got (" + std::to_string(t.point.x) + ", " + std::to_string(t.point.y) + ")");
        if (!known_people.empty() && std::find(known_people.begin(), known_people.end(), t.person) == known_people.end())
            throw std::invalid_argument("resolve_tags: expected tags of known people, got '" + t.person + "'");
    }
    auto distance = [&](const PhotoTag& t, const Detection& f) {
        const cv::Point2f c(f.box.x + f.box.width / 2.f, f.box.y + f.box.height / 2.f);
        return double(cv::norm(t.point - c)) / std::max(1, f.box.width);
    };
    std::vector<TagResolution> out(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) {
        TagResolution& r = out[i];
        r.tag = tags[i];
        double best = 0;
        for (std::size_t k = 0; k < faces.size(); ++k) {
            const double d = distance(tags[i], faces[k]);
            if (r.face < 0 || d < best) best = d, r.face = int(k);
        }
        r.distance = best;
        if (r.face < 0) {
            r.outcome = TagOutcome::NoFaceNearby;
            r.reason = "no face was detected in the photo";
        } else if (best > params.max_distance) {
            r.outcome = TagOutcome::NoFaceNearby;
            r.reason = "the nearest face is " + std::to_string(best).substr(0, 4) + " face widths away";
        } else if (is_profile(faces[std::size_t(r.face)].pose)) {
            r.outcome = TagOutcome::NearestIsProfile;
            r.reason = "the nearest face is a profile; the next frontal face may be someone else";
        } else {
            r.outcome = TagOutcome::Resolved;
            r.reason = "nearest face, frontal";
        }
    }
    // One tag per face: the nearest tag keeps a contested face.
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out[i].outcome != TagOutcome::Resolved) continue;
        for (std::size_t j = 0; j < out.size(); ++j) {
            if (j == i || out[j].face != out[i].face || out[j].outcome == TagOutcome::NoFaceNearby) continue;
            if (out[j].distance < out[i].distance || (out[j].distance == out[i].distance && j < i)) {
                out[i].outcome = TagOutcome::FaceTaken;
                out[i].reason = "the nearest face is nearer to the tag of '" + out[j].tag.person + "'";
                break;
            }
        }
    }
    return out;
}

}  // namespace facesocial
