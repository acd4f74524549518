// Tagged photos as training data (paper section III.C.4): a social network gives, per tag, a
// person and a rough point on the photo. Each tag is resolved to the detected face nearest to
// its point; when that face is a profile the tag yields nothing (never the next frontal face,
// which may be someone else); otherwise the face becomes a training sample of the person.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/detection.hpp"

namespace facesocial {

/// One tag of a photo: who, and roughly where.
struct PhotoTag {
    std::string person;
    cv::Point2f point;  ///< pixels, inside the photo
};

/// What became of a tag.
enum class TagOutcome {
    Resolved,          ///< the nearest face is frontal and near enough: a training sample
    NearestIsProfile,  ///< the nearest face is a profile: refused
    NoFaceNearby,      ///< no detected face within max_distance of the point
    FaceTaken,         ///< the nearest face is nearer to another tag of the photo
};

/// "resolved", "nearest_is_profile", "no_face_nearby", "face_taken".
std::string to_string(TagOutcome outcome);

struct TagResolution {
    PhotoTag tag;
    TagOutcome outcome = TagOutcome::NoFaceNearby;
    int face = -1;         ///< index into the detections: the nearest face (-1 when none)
    double distance = 0;   ///< from the tag point to that face's centre, in face widths
    std::string reason;    ///< one sentence for people
};

struct TagResolverParams {
    /// A tag farther than this (in widths of the face) from the nearest face's centre resolves
    /// to nothing.
    double max_distance = 1.5;
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// Resolves every tag against the faces detected in a photo of `image_size`. A face goes to at
/// most one tag (the nearest one). If `known_people` is not empty, every tagged person must be
/// in it. Throws std::invalid_argument for a tag outside the photo, with an empty or unknown
/// person, or for a person tagged twice in the photo.
std::vector<TagResolution> resolve_tags(const std::vector<Detection>& faces, const std::vector<PhotoTag>& tags,
                                        cv::Size image_size, const TagResolverParams& params = {},
                                        const std::vector<std::string>& known_people = {});

}  // namespace facesocial
