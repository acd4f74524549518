// The compiled part of the `facesocial` Python package.
#include "common.hpp"
#include "facesocial/version.hpp"

PYBIND11_MODULE(_facesocial, m) {
    using namespace facesocial::python;
    m.doc() = "FaceSocial: face detection, normalisation and embedded-HMM recognition for social robots.";
    m.attr("__version__") = FACESOCIAL_VERSION_STRING;
    bind_errors(m);
    bind_detection(m);
    bind_preprocess(m);
    bind_io(m);
    bind_recognition(m);
    bind_video(m);
    bind_social(m);
}
