// Access to the face sets under the data root ($FACESOCIAL_DATA): the layouts the benchmarks,
// tests and tools read. No image is bundled with the library.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/face_normalizer.hpp"

namespace facesocial {

/// The data root: $FACESOCIAL_DATA. Throws FileError when the variable is unset or does not
/// name a directory.
std::filesystem::path data_root();

/// One image with hand-drawn face boxes.
struct AnnotatedImage {
    std::filesystem::path file;    ///< absolute image path
    std::vector<cv::Rect> faces;   ///< ground-truth boxes
};

/// Reads a dlib imglab XML file (<image file=...><box top left width height/>...). Image paths
/// are resolved against the XML's folder. Throws FileError / ModelFormatError on a missing or
/// malformed file.
std::vector<AnnotatedImage> load_imglab_xml(const std::filesystem::path& xml);

/// The 43 annotated faces of dlib_faces: training.xml followed by testing.xml.
std::vector<AnnotatedImage> load_dlib_faces(const std::filesystem::path& root);

/// The images of one person.
struct PersonImages {
    std::string name;
    std::vector<std::filesystem::path> images;  ///< sorted in natural order
};

/// A folder holding one sub-folder of images per person (ORL, Essex train/, ...). People are
/// sorted by natural order of their folder names ("s2" before "s10"); folders without images are
/// skipped. Throws FileError when `folder` is not a directory or holds no person.
std::vector<PersonImages> load_identity_folders(const std::filesystem::path& folder);

/// Identity folders loaded as normalised faces, one list per person.
struct FaceSet {
    std::vector<std::string> names;            ///< folder names, natural order
    std::vector<std::vector<cv::Mat>> faces;   ///< faces[p]: person p's normalised faces (CV_32F)
};

/// Loads load_identity_folders(folder), normalising every whole image as one cropped face
/// (grey). Throws FileError for a missing folder or an unreadable image.
FaceSet load_cropped_faces(const std::filesystem::path& folder,
                           const NormalizerParams& params = NormalizerParams::cropped());

/// Natural-order comparison of names: digit runs compare as numbers.
bool natural_less(const std::string& a, const std::string& b);

}  // namespace facesocial
