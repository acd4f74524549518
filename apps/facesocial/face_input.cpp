#include "face_input.hpp"

#include <algorithm>

namespace facesocial::cli {

std::unique_ptr<FrontEnd> make_front_end(bool detect) {
    if (!detect) return nullptr;
    return std::make_unique<FrontEnd>(FrontEndParams{});
}

std::vector<FaceInput> faces_of(const cv::Mat& image, const ClassifierBank& bank, const FrontEnd* front_end) {
    if (!front_end) return {FaceInput{cv::Rect(0, 0, image.cols, image.rows), bank.normalize(image)}};
    std::vector<FaceInput> out;
    for (const FrontEndFace& f : front_end->process(image).faces)
        out.push_back({f.detection.box, bank.normalize(image, f.detection.box)});
    std::stable_sort(out.begin(), out.end(), [](const FaceInput& a, const FaceInput& b) { return a.box.area() > b.box.area(); });
    return out;
}

}  // namespace facesocial::cli
