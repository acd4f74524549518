#include "facesocial/front_end.hpp"

#include "checks.hpp"

namespace facesocial {

void FrontEndParams::validate() const {
    frontal.validate();
    if (frontal.kind != CascadeKind::Frontal)
        throw std::invalid_argument("FrontEndParams: expected frontal.kind Frontal, got Profile");
    if (use_profile) {
        profile.validate();
        if (profile.kind != CascadeKind::Profile)
            throw std::invalid_argument("FrontEndParams: expected profile.kind Profile, got Frontal");
    }
    merge.validate();
    skin.validate();
    normalizer.validate();
}

namespace {
std::unique_ptr<FaceDetector> make_detector(const FrontEndParams& p) {
    p.validate();
    std::vector<std::shared_ptr<FaceDetector>> parts;
    parts.push_back(FaceDetector::create(p.frontal));
    if (p.use_profile) parts.push_back(FaceDetector::create(p.profile));
    return FaceDetector::combine(std::move(parts), p.merge);
}
}  // namespace

FrontEnd::FrontEnd(const FrontEndParams& params)
    : params_(params), detector_(make_detector(params)), skin_(params.skin), normalizer_(params.normalizer) {}

FrontEndResult FrontEnd::process(const cv::Mat& image) const {
    detail::require_8bit_grey_or_bgr(image, "FrontEnd::process");
    const std::vector<Detection> candidates = detector_->detect(image);
    FrontEndResult result;
    std::vector<Detection> kept = candidates;
    std::vector<double> fractions(candidates.size(), -1.0);
    if (params_.use_skin_filter) {
        SkinFilterResult s = skin_.filter(image, candidates);
        result.skin_filter_skipped = s.skipped;
        kept = std::move(s.kept);
        fractions = std::move(s.kept_fraction);
        result.rejected = std::move(s.rejected);
        result.rejected_skin = std::move(s.rejected_fraction);
    }
    result.faces.reserve(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
        FrontEndFace f{kept[i], fractions[i], {}};
        if (params_.normalize) f.face = normalizer_.normalize(image, kept[i].box);
        result.faces.push_back(std::move(f));
    }
    return result;
}

}  // namespace facesocial
