// The front end after detection: skin filter, elliptical normalisation, the whole per-frame front
// end, and training-set augmentation.
#include "common.hpp"
#include "facesocial/face_augment.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/skin_filter.hpp"

namespace facesocial::python {

namespace {

py::tuple normalized_tuple(const NormalizedFace& f) { return py::make_tuple(array_from_mat(f.pixels), array_from_mat(f.mask)); }

}  // namespace

void bind_preprocess(py::module_& m) {
    // --- skin filter ---------------------------------------------------------------------------
    py::enum_<SkinRule>(m, "SkinRule", "Published RGB skin rules (Peer, Kovac & Solina 2003).")
        .value("PEER_DAYLIGHT", SkinRule::PeerDaylight)
        .value("PEER_DAYLIGHT_OR_FLASH", SkinRule::PeerDaylightOrFlash);
    ParamsClass<SkinFilterParams>(m, "SkinFilterParams", "Parameters of the skin filter.")
        .field("rule", &SkinFilterParams::rule, "per-pixel rule")
        .field("min_skin_fraction", &SkinFilterParams::min_skin_fraction, "candidates with less skin are dropped")
        .field("ellipse_only", &SkinFilterParams::ellipse_only, "count only pixels inside the box's ellipse")
        .field("grey_tolerance", &SkinFilterParams::grey_tolerance,
               "a BGR image whose channels never differ by more than this is grey: filter skipped")
        .done();
    py::class_<SkinFilterResult>(m, "SkinFilterResult", "Outcome of filtering one frame's candidates.")
        .def_readonly("kept", &SkinFilterResult::kept)
        .def_readonly("rejected", &SkinFilterResult::rejected)
        .def_readonly("kept_fraction", &SkinFilterResult::kept_fraction, "-1 when skipped")
        .def_readonly("rejected_fraction", &SkinFilterResult::rejected_fraction)
        .def_readonly("skipped", &SkinFilterResult::skipped, "grey image: nothing filtered")
        .def("__repr__", [](const SkinFilterResult& r) {
            return "SkinFilterResult(kept=" + std::to_string(r.kept.size()) + ", rejected=" +
                   std::to_string(r.rejected.size()) + (r.skipped ? ", skipped" : "") + ")";
        });
    py::class_<SkinFilter>(m, "SkinFilter", "Skin-colour filtering of face candidates; thread-safe.")
        .def(py::init<const SkinFilterParams&>(), py::arg("params") = SkinFilterParams{})
        .def_property_readonly("params", &SkinFilter::params)
        .def(
            "skin_mask",
            [](const SkinFilter& f, const py::array& bgr) {
                const cv::Mat img = mat_from_array(bgr, ArrayKind::Image, "SkinFilter.skin_mask");
                cv::Mat mask;
                {
                    py::gil_scoped_release release;
                    mask = f.skin_mask(img);
                }
                return array_from_mat(mask);
            },
            py::arg("bgr"), "uint8 (H, W) mask, 255 = skin, of a BGR image.")
        .def(
            "skin_fraction",
            [](const SkinFilter& f, const py::array& bgr, const py::tuple& box) {
                return f.skin_fraction(mat_from_array(bgr, ArrayKind::Image, "SkinFilter.skin_fraction"),
                                       rect_from_tuple(box, "SkinFilter.skin_fraction"));
            },
            py::arg("bgr"), py::arg("box"), "Share of skin pixels in the box, in [0, 1].")
        .def(
            "is_grey",
            [](const SkinFilter& f, const py::array& image) {
                return f.is_grey(mat_from_array(image, ArrayKind::Image, "SkinFilter.is_grey"));
            },
            py::arg("image"))
        .def(
            "filter",
            [](const SkinFilter& f, const py::array& image, const std::vector<Detection>& candidates) {
                const cv::Mat img = mat_from_array(image, ArrayKind::Image, "SkinFilter.filter");
                py::gil_scoped_release release;
                return f.filter(img, candidates);
            },
            py::arg("image"), py::arg("candidates"), "Keeps candidates with enough skin (all of them for a grey image).");

    // --- normalisation -------------------------------------------------------------------------
    ParamsClass<NormalizerParams>(m, "NormalizerParams", "Parameters of the face normaliser.")
        .property(
            "output_size", [](const NormalizerParams& p) { return tuple_from_size(p.output_size); },
            [](NormalizerParams& p, const py::tuple& t) { p.output_size = size_from_tuple(t, "NormalizerParams.output_size"); },
            "(width, height) of the normalised face")
        .field("ellipse_width", &NormalizerParams::ellipse_width, "ellipse semi-axis, share of half the width")
        .field("ellipse_height", &NormalizerParams::ellipse_height, "ellipse semi-axis, share of half the height")
        .field("elliptical_mask", &NormalizerParams::elliptical_mask, "mask the background with the ellipse")
        .field("equalize", &NormalizerParams::equalize, "histogram equalisation before the statistics")
        .field("vertical_margin", &NormalizerParams::vertical_margin, "box grown by this share of its height above and below")
        .done()
        .def_static("cropped", &NormalizerParams::cropped, "For faces already tightly cropped (ORL): no mask.");
    py::class_<FaceNormalizer>(m, "FaceNormalizer", "Face box -> fixed-size float32 face for the classifiers.")
        .def(py::init<const NormalizerParams&>(), py::arg("params") = NormalizerParams{})
        .def_property_readonly("params", &FaceNormalizer::params)
        .def(
            "normalize",
            [](const FaceNormalizer& n, const py::array& image, const std::optional<py::tuple>& box) {
                const cv::Mat img = mat_from_array(image, ArrayKind::Image, "FaceNormalizer.normalize");
                const std::optional<cv::Rect> r =
                    box ? std::optional<cv::Rect>(rect_from_tuple(*box, "FaceNormalizer.normalize")) : std::nullopt;
                NormalizedFace f;
                {
                    py::gil_scoped_release release;
                    f = r ? n.normalize(img, *r) : n.normalize(img);
                }
                return normalized_tuple(f);
            },
            py::arg("image"), py::arg("box") = py::none(),
            "(pixels float32 (h, w), mask uint8 (h, w)) of the box, or of the whole image when box is None.")
        .def_static(
            "to_8bit",
            [](const py::array& pixels, const py::array& mask) {
                NormalizedFace f{mat_from_array(pixels, ArrayKind::Grey, "FaceNormalizer.to_8bit").clone(),
                                 mat_from_array(mask, ArrayKind::GreyU8, "FaceNormalizer.to_8bit").clone()};
                if (f.pixels.type() != CV_32F)
                    throw std::invalid_argument("FaceNormalizer.to_8bit: expected float32 pixels, got uint8");
                return array_from_mat(FaceNormalizer::to_8bit(f));
            },
            py::arg("pixels"), py::arg("mask"), "A uint8 picture of a normalised face for display.");

    // --- the front end -------------------------------------------------------------------------
    ParamsClass<FrontEndParams>(m, "FrontEndParams", "Parameters of the per-frame front end.")
        .field("frontal", &FrontEndParams::frontal, "the frontal detector")
        .field("use_profile", &FrontEndParams::use_profile, "also run the profile detector")
        .field("profile", &FrontEndParams::profile, "the profile detector")
        .field("merge", &FrontEndParams::merge, "merging of frontal and profile detections")
        .field("use_skin_filter", &FrontEndParams::use_skin_filter, "drop candidates with too little skin")
        .field("skin", &FrontEndParams::skin, "the skin rule and threshold")
        .field("normalize", &FrontEndParams::normalize, "produce normalised faces")
        .field("normalizer", &FrontEndParams::normalizer, "the normalised face")
        .done();
    py::class_<FrontEndFace>(m, "FrontEndFace", "One face that passed the front end.")
        .def_readonly("detection", &FrontEndFace::detection)
        .def_readonly("skin_fraction", &FrontEndFace::skin_fraction, "-1 when the skin filter did not run")
        .def_property_readonly(
            "pixels", [](const FrontEndFace& f) { return array_from_mat(f.face.pixels); },
            "normalised face, float32 (h, w); empty when normalisation is off")
        .def_property_readonly("mask", [](const FrontEndFace& f) { return array_from_mat(f.face.mask); })
        .def("__repr__", [](const FrontEndFace& f) {
            return "FrontEndFace(" + py::repr(py::cast(f.detection)).cast<std::string>() + ")";
        });
    py::class_<FrontEndResult>(m, "FrontEndResult", "What the front end found in one frame.")
        .def_readonly("faces", &FrontEndResult::faces, "surviving faces, by decreasing confidence")
        .def_readonly("rejected", &FrontEndResult::rejected, "candidates the skin filter dropped")
        .def_readonly("rejected_skin", &FrontEndResult::rejected_skin)
        .def_readonly("skin_filter_skipped", &FrontEndResult::skin_filter_skipped)
        .def("__repr__", [](const FrontEndResult& r) {
            return "FrontEndResult(faces=" + std::to_string(r.faces.size()) + ", rejected=" +
                   std::to_string(r.rejected.size()) + ")";
        });
    py::class_<FrontEnd>(m, "FrontEnd", "detect -> skin filter -> normalise, per frame; thread-safe.")
        .def(py::init<const FrontEndParams&>(), py::arg("params") = FrontEndParams{})
        .def_property_readonly("params", &FrontEnd::params)
        .def(
            "process",
            [](const FrontEnd& f, const py::array& image) {
                const cv::Mat img = mat_from_array(image, ArrayKind::Image, "FrontEnd.process");
                py::gil_scoped_release release;
                return f.process(img);
            },
            py::arg("image"), "Runs the front end on a uint8 grey or BGR frame.");

    // --- augmentation --------------------------------------------------------------------------
    ParamsClass<AugmentParams>(m, "AugmentParams", "Ranges of the random variations of augment_faces.")
        .field("max_rotation_deg", &AugmentParams::max_rotation_deg, "in-plane head roll")
        .field("max_shift", &AugmentParams::max_shift, "translation, share of the image size")
        .field("max_scale", &AugmentParams::max_scale, "relative zoom")
        .field("mirror", &AugmentParams::mirror, "flip left-right with probability 1/2")
        .field("max_gain", &AugmentParams::max_gain, "relative contrast change")
        .field("max_bias", &AugmentParams::max_bias, "brightness change, share of the range")
        .done();
    m.def(
        "augment_faces",
        [](const std::vector<py::array>& faces, std::size_t count, const AugmentParams& params, uint32_t seed) {
            const std::vector<cv::Mat> in = mats_from_list(faces, ArrayKind::Grey, "augment_faces");
            std::vector<cv::Mat> out;
            {
                py::gil_scoped_release release;
                out = augment_faces(in, count, params, seed);
            }
            return list_from_mats(out);
        },
        py::arg("faces"), py::arg("count"), py::arg("params") = AugmentParams{}, py::arg("seed") = 0,
        "`count` faces: the originals first, then seeded random variations of them.");
}

}  // namespace facesocial::python
