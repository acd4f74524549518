// A robot's project using the installed library: builds a front end and normalises a face.
#include <iostream>

#include <facesocial/facesocial.hpp>

int main() {
    facesocial::FaceNormalizer normalizer;
    cv::Mat grey(112, 92, CV_8UC1);
    cv::randu(grey, 0, 255);
    const auto face = normalizer.normalize(grey);
    const bool ok = face.pixels.size() == cv::Size(92, 112) &&
                    facesocial::default_cascade_file(facesocial::CascadeKind::Frontal).size() > 0;
    std::cout << "facesocial " << FACESOCIAL_VERSION_STRING << (ok ? " ok" : " broken") << "\n";
    return ok ? 0 : 1;
}
