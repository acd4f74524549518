// Face detection: detections, cascade parameters, detectors and their combination, merging.
#include "common.hpp"
#include "facesocial/detection.hpp"
#include "facesocial/face_detector.hpp"

namespace facesocial::python {

void bind_detection(py::module_& m) {
    py::enum_<FacePose>(m, "FacePose", "Head pose class of a detection.")
        .value("FRONTAL", FacePose::Frontal)
        .value("PROFILE_LEFT", FacePose::ProfileLeft)
        .value("PROFILE_RIGHT", FacePose::ProfileRight);
    py::enum_<CascadeKind>(m, "CascadeKind", "Which face model a cascade detector runs.")
        .value("FRONTAL", CascadeKind::Frontal)
        .value("PROFILE", CascadeKind::Profile);

    py::class_<Detection>(m, "Detection", "One face candidate in image coordinates.")
        .def(py::init([](const py::tuple& box, FacePose pose, float confidence) {
                 return Detection{rect_from_tuple(box, "Detection"), pose, confidence};
             }),
             py::arg("box"), py::arg("pose") = FacePose::Frontal, py::arg("confidence") = 0.f)
        .def_property(
            "box", [](const Detection& d) { return tuple_from_rect(d.box); },
            [](Detection& d, const py::tuple& t) { d.box = rect_from_tuple(t, "Detection.box"); },
            "(x, y, width, height) in pixels")
        .def_readwrite("pose", &Detection::pose)
        .def_readwrite("confidence", &Detection::confidence, "in (0, 1)")
        .def_property_readonly("is_profile", [](const Detection& d) { return is_profile(d.pose); })
        .def("__repr__", [](const Detection& d) {
            return "Detection(box=(" + std::to_string(d.box.x) + ", " + std::to_string(d.box.y) + ", " +
                   std::to_string(d.box.width) + ", " + std::to_string(d.box.height) + "), pose=" + to_string(d.pose) +
                   ", confidence=" + py::repr(py::float_(d.confidence)).cast<std::string>() + ")";
        });

    m.def(
        "iou", [](const py::tuple& a, const py::tuple& b) { return iou(rect_from_tuple(a, "iou"), rect_from_tuple(b, "iou")); },
        py::arg("a"), py::arg("b"), "Intersection over union of two (x, y, w, h) boxes.");

    ParamsClass<MergeParams>(m, "MergeParams", "How overlapping detections are merged.")
        .field("iou_threshold", &MergeParams::iou_threshold, "boxes overlapping at least this much are one face")
        .field("containment_threshold", &MergeParams::containment_threshold,
               "... or when this share of the smaller box is covered")
        .field("prefer_frontal", &MergeParams::prefer_frontal, "a frontal box wins over a profile box it overlaps")
        .done();
    m.def("merge_detections", &merge_detections, py::arg("detections"), py::arg("params") = MergeParams{},
          "Greedy non-maximum suppression; sorted by decreasing confidence.");

    ParamsClass<CascadeDetectorParams>(m, "CascadeDetectorParams", "Parameters of a Viola-Jones cascade detector.")
        .field("kind", &CascadeDetectorParams::kind, "frontal or profile model")
        .field("cascade_file", &CascadeDetectorParams::cascade_file,
               "cascade XML; empty: the default for the kind, looked up in /usr/share/opencv4")
        .field("scale_factor", &CascadeDetectorParams::scale_factor, "step between pyramid scales, > 1")
        .field("min_neighbors", &CascadeDetectorParams::min_neighbors, "raw windows that must agree, >= 1")
        .field("min_face_size", &CascadeDetectorParams::min_face_size, "smallest face side searched, pixels")
        .field("max_face_size", &CascadeDetectorParams::max_face_size, "largest face side searched; 0 = no limit")
        .field("max_working_width", &CascadeDetectorParams::max_working_width,
               "wider frames are downscaled before detection; 0 = full resolution")
        .field("equalize", &CascadeDetectorParams::equalize, "histogram-equalise the grey frame first")
        .field("mirror_profile", &CascadeDetectorParams::mirror_profile, "profile: also run on the mirrored image")
        .field("merge", &CascadeDetectorParams::merge, "merging of direct and mirrored profile detections")
        .done()
        .def_static("fast_frontal", &CascadeDetectorParams::fast_frontal,
                    "Preset for live 640x480 video on one core (LBP cascade, 320 px working width).")
        .def_static("fast_profile", &CascadeDetectorParams::fast_profile,
                    "The same for the profile model (LBP profile cascade, 320 px working width).")
        .def_static("profile", &profile_cascade_params, "Default params of a profile detector.");

    py::class_<FaceDetector, std::shared_ptr<FaceDetector>>(m, "FaceDetector",
                                                            "A face detector; safe to call from several threads.")
        .def_static(
            "create", [](const CascadeDetectorParams& p) { return std::shared_ptr<FaceDetector>(FaceDetector::create(p)); },
            py::arg("params") = CascadeDetectorParams{},
            "A cascade detector. Raises FileError for a missing cascade, ValueError for invalid params.")
        .def_static(
            "combine",
            [](std::vector<std::shared_ptr<FaceDetector>> parts, const MergeParams& merge) {
                return std::shared_ptr<FaceDetector>(FaceDetector::combine(std::move(parts), merge));
            },
            py::arg("parts"), py::arg("merge") = MergeParams{},
            "Runs every detector on the same frame (in parallel) and merges overlapping detections.")
        .def_static(
            "default", [](bool with_profile) { return std::shared_ptr<FaceDetector>(create_default_detector(with_profile)); },
            py::arg("with_profile") = false, "The frontal (and profile) cascades with default params, combined.")
        .def(
            "detect",
            [](const FaceDetector& d, const py::array& image) {
                const cv::Mat img = mat_from_array(image, ArrayKind::Image, "FaceDetector.detect");
                py::gil_scoped_release release;
                return d.detect(img);
            },
            py::arg("image"), "Detections in a uint8 grey (H, W) or BGR (H, W, 3) image, by decreasing confidence.")
        .def_property_readonly("name", &FaceDetector::name)
        .def("__repr__", [](const FaceDetector& d) { return "FaceDetector('" + d.name() + "')"; });
}

}  // namespace facesocial::python
