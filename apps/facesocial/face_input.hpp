// How the bank commands turn image files into normalised faces: the whole image as one cropped
// face, or (--detect) every face the front end finds.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/front_end.hpp"

namespace facesocial::cli {

struct FaceInput {
    cv::Rect box;  ///< where the face is in the image (the whole image without detection)
    cv::Mat face;  ///< normalised with the bank's normaliser
};

/// Detection for --detect: frontal cascade and skin filter.
std::unique_ptr<FrontEnd> make_front_end(bool detect);

/// Faces of one image, largest first. Without a front end the whole image is one face.
std::vector<FaceInput> faces_of(const cv::Mat& image, const ClassifierBank& bank, const FrontEnd* front_end);

}  // namespace facesocial::cli
