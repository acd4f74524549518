#include "common.hpp"

#include <cstring>
#include <stdexcept>

namespace facesocial::python {

namespace {

std::string describe(const py::array& a) {
    std::string s = "dtype " + py::str(a.dtype()).cast<std::string>() + ", shape (";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) {
        if (i) s += ", ";
        s += std::to_string(a.shape(i));
    }
    if (a.ndim() == 1) s += ',';
    return s + ")";
}

[[noreturn]] void fail(const std::string& what, const std::string& expected, const py::array& a,
                       const std::string& detail = {}) {
    throw std::invalid_argument(what + ": expected " + expected + ", got " + describe(a) + detail);
}

}  // namespace

cv::Mat mat_from_array(const py::array& a, ArrayKind kind, const std::string& what) {
    const bool u8 = a.dtype().is(py::dtype::of<uint8_t>());
    const bool f32 = a.dtype().is(py::dtype::of<float>());
    std::string expected;
    bool ok = false;
    switch (kind) {
    case ArrayKind::Image:
        expected = "a uint8 array of shape (H, W) or (H, W, 3)";
        ok = u8 && (a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 3));
        break;
    case ArrayKind::Grey:
        expected = "a uint8 or float32 array of shape (H, W)";
        ok = (u8 || f32) && a.ndim() == 2;
        break;
    case ArrayKind::GreyU8:
        expected = "a uint8 array of shape (H, W)";
        ok = u8 && a.ndim() == 2;
        break;
    }
    if (!ok) fail(what, expected, a);
    if (a.shape(0) == 0 || a.shape(1) == 0) fail(what, "a non-empty image", a);
    if (!(a.flags() & py::array::c_style))
        fail(what, expected + " in C order", a, " that is not C-contiguous (use numpy.ascontiguousarray)");
    const int channels = a.ndim() == 3 ? int(a.shape(2)) : 1;
    const int type = CV_MAKETYPE(u8 ? CV_8U : CV_32F, channels);
    // The Mat only reads; the library never writes into its inputs.
    return cv::Mat(int(a.shape(0)), int(a.shape(1)), type, const_cast<void*>(a.data()));
}

py::array array_from_mat(const cv::Mat& mat) {
    if (mat.empty()) return py::array_t<uint8_t>(std::vector<py::ssize_t>{0, 0});
    const int depth = mat.depth();
    if (depth != CV_8U && depth != CV_32F)
        throw std::logic_error("array_from_mat: unexpected matrix type " + std::to_string(mat.type()));
    const py::dtype dtype = depth == CV_8U ? py::dtype::of<uint8_t>() : py::dtype::of<float>();
    std::vector<py::ssize_t> shape{mat.rows, mat.cols};
    if (mat.channels() > 1) shape.push_back(mat.channels());
    py::array out(dtype, shape);
    const std::size_t row_bytes = std::size_t(mat.cols) * mat.elemSize();
    auto* dst = static_cast<uint8_t*>(out.mutable_data());
    for (int r = 0; r < mat.rows; ++r) std::memcpy(dst + r * row_bytes, mat.ptr(r), row_bytes);
    return out;
}

std::vector<cv::Mat> mats_from_list(const std::vector<py::array>& arrays, ArrayKind kind, const std::string& what) {
    std::vector<cv::Mat> out;
    out.reserve(arrays.size());
    for (std::size_t i = 0; i < arrays.size(); ++i)
        out.push_back(mat_from_array(arrays[i], kind, what + "[" + std::to_string(i) + "]"));
    return out;
}

py::list list_from_mats(const std::vector<cv::Mat>& mats) {
    py::list out;
    for (const cv::Mat& m : mats) out.append(array_from_mat(m));
    return out;
}

py::array_t<double> array_from_vector(const std::vector<double>& values) {
    py::array_t<double> out(py::ssize_t(values.size()));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::tuple tuple_from_rect(const cv::Rect& r) { return py::make_tuple(r.x, r.y, r.width, r.height); }

cv::Rect rect_from_tuple(const py::tuple& t, const std::string& what) {
    if (t.size() != 4)
        throw std::invalid_argument(what + ": expected a box (x, y, width, height), got a tuple of " +
                                    std::to_string(t.size()));
    return {t[0].cast<int>(), t[1].cast<int>(), t[2].cast<int>(), t[3].cast<int>()};
}

py::tuple tuple_from_size(const cv::Size& s) { return py::make_tuple(s.width, s.height); }

cv::Size size_from_tuple(const py::tuple& t, const std::string& what) {
    if (t.size() != 2)
        throw std::invalid_argument(what + ": expected a size (width, height), got a tuple of " +
                                    std::to_string(t.size()));
    return {t[0].cast<int>(), t[1].cast<int>()};
}

}  // namespace facesocial::python
