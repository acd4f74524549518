// Image files and the face sets under the data root.
#include "common.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::python {

void bind_io(py::module_& m) {
    py::enum_<ImageColor>(m, "ImageColor", "How load_image returns the pixels.")
        .value("BGR", ImageColor::Bgr, "uint8 (H, W, 3); grey files are expanded")
        .value("GREY", ImageColor::Grey, "uint8 (H, W); colour files are converted")
        .value("ANY", ImageColor::Any, "uint8 (H, W) or (H, W, 3), as stored");

    m.def(
        "load_image",
        [](const std::filesystem::path& path, ImageColor color) {
            cv::Mat img;
            {
                py::gil_scoped_release release;
                img = load_image(path, color);
            }
            return array_from_mat(img);
        },
        py::arg("path"), py::arg("color") = ImageColor::Bgr,
        "Reads an image file into a uint8 array. Raises FileError when it is missing or not an image.");
    m.def(
        "save_image",
        [](const std::filesystem::path& path, const py::array& image) {
            save_image(path, mat_from_array(image, ArrayKind::Image, "save_image"));
        },
        py::arg("path"), py::arg("image"), "Writes a uint8 grey or BGR image; raises FileError on failure.");
    m.def("list_images", &list_images, py::arg("folder"),
          "Image files directly inside a folder, in natural order. Raises FileError for a missing folder.");
    m.def("has_image_extension", &has_image_extension, py::arg("path"));
    m.def("data_root", &data_root, "The data root $FACESOCIAL_DATA; raises FileError when unset or missing.");

    m.def(
        "load_identity_folders",
        [](const std::filesystem::path& folder) {
            py::list out;
            for (const PersonImages& p : load_identity_folders(folder)) out.append(py::make_tuple(p.name, p.images));
            return out;
        },
        py::arg("folder"),
        "[(name, [image paths])] for a folder holding one sub-folder of images per person, in natural order.");

    py::class_<FaceSet>(m, "FaceSet", "Identity folders loaded as normalised faces.")
        .def_readonly("names", &FaceSet::names, "folder names, natural order")
        .def_property_readonly(
            "faces",
            [](const FaceSet& s) {
                py::list out;
                for (const auto& person : s.faces) out.append(list_from_mats(person));
                return out;
            },
            "faces[p]: person p's normalised faces (float32 arrays)")
        .def("__len__", [](const FaceSet& s) { return s.names.size(); })
        .def("__repr__", [](const FaceSet& s) {
            std::size_t n = 0;
            for (const auto& p : s.faces) n += p.size();
            return "FaceSet(" + std::to_string(s.names.size()) + " people, " + std::to_string(n) + " faces)";
        });
    m.def(
        "load_cropped_faces",
        [](const std::filesystem::path& folder, const NormalizerParams& params) {
            py::gil_scoped_release release;
            return load_cropped_faces(folder, params);
        },
        py::arg("folder"), py::arg("params") = NormalizerParams::cropped(),
        "Loads identity folders of already cropped faces, each image normalised as one face (grey).");
}

}  // namespace facesocial::python
