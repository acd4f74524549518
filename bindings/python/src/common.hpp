// Shared pieces of the binding layer: numpy <-> cv::Mat conversion with clear errors, geometry
// as tuples, and a helper that binds a Params struct with attributes, keyword construction,
// validation and a readable repr. No algorithm lives here.
#pragma once

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

namespace facesocial::python {

namespace py = pybind11;

/// What an array argument may hold.
enum class ArrayKind {
    Image,     ///< uint8, (H, W) grey or (H, W, 3) BGR
    Grey,      ///< uint8 (H, W) or float32 (H, W): a single-channel face
    GreyU8,    ///< uint8 (H, W)
};

/// A cv::Mat header over the array's memory (no copy). The array must stay alive while the Mat
/// is used; the binding functions keep it as their argument. Throws std::invalid_argument
/// (Python ValueError) naming `what`, the expected layout and what came: a wrong dtype, number
/// of dimensions, channel count, an empty or a non-C-contiguous array.
cv::Mat mat_from_array(const py::array& array, ArrayKind kind, const std::string& what);

/// A new numpy array holding a copy of `mat` (uint8 or float32; 1 channel gives (H, W),
/// n channels (H, W, n)).
py::array array_from_mat(const cv::Mat& mat);

/// Lists of arrays.
std::vector<cv::Mat> mats_from_list(const std::vector<py::array>& arrays, ArrayKind kind, const std::string& what);
py::list list_from_mats(const std::vector<cv::Mat>& mats);

/// A 1-D float64 array of the values.
py::array_t<double> array_from_vector(const std::vector<double>& values);

/// Boxes are (x, y, width, height) tuples; sizes (width, height).
py::tuple tuple_from_rect(const cv::Rect& r);
cv::Rect rect_from_tuple(const py::tuple& t, const std::string& what);
py::tuple tuple_from_size(const cv::Size& s);
cv::Size size_from_tuple(const py::tuple& t, const std::string& what);

/// Binds a Params struct: attributes (def_readwrite or properties), `T(**fields)` construction
/// that rejects unknown names and validates, `validate()`, `__repr__` listing every field, and
/// `__eq__` by fields.
template <class T>
class ParamsClass {
public:
    ParamsClass(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc), name_(name) {}

    template <class D>
    ParamsClass& field(const char* name, D T::*member, const char* doc) {
        cls_.def_readwrite(name, member, doc);
        fields_.push_back(name);
        return *this;
    }
    /// A field stored as another C++ type (cv::Size as a tuple).
    template <class Get, class Set>
    ParamsClass& property(const char* name, Get get, Set set, const char* doc) {
        cls_.def_property(name, get, set, doc);
        fields_.push_back(name);
        return *this;
    }
    /// Finishes the class; returns it for extra methods.
    py::class_<T>& done() {
        const std::vector<std::string> fields = fields_;
        const std::string name = name_;
        cls_.def(py::init([fields, name](const py::kwargs& kwargs) {
                     py::object self = py::cast(T{});
                     for (const auto& item : kwargs) {
                         const std::string key = py::str(item.first);
                         if (std::find(fields.begin(), fields.end(), key) == fields.end())
                             throw py::type_error(name + ": unknown field '" + key + "'");
                         py::setattr(self, item.first, item.second);
                     }
                     T value = self.cast<T>();
                     value.validate();
                     return value;
                 }),
                 ("Defaults, overridden by keyword: " + name + "(field=value, ...). Raises ValueError when invalid.")
                     .c_str());
        cls_.def("validate", &T::validate, "Raises ValueError naming the first invalid field.");
        cls_.def("__repr__", [fields, name](const py::object& self) {
            std::string s = name + "(";
            for (std::size_t i = 0; i < fields.size(); ++i) {
                if (i) s += ", ";
                s += fields[i];
                s += '=';
                s += py::repr(self.attr(fields[i].c_str())).cast<std::string>();
            }
            s += ')';
            return s;
        });
        cls_.def("__eq__", [fields](const py::object& a, const py::object& b) {
            if (!py::isinstance(b, py::type::of(a))) return false;
            for (const auto& f : fields)
                if (!a.attr(f.c_str()).equal(b.attr(f.c_str()))) return false;
            return true;
        });
        cls_.attr("__hash__") = py::none();
        cls_.def(py::pickle(
            [fields](const py::object& self) {
                py::dict d;
                for (const auto& f : fields) d[f.c_str()] = self.attr(f.c_str());
                return d;
            },
            [](const py::dict& d) {
                py::object self = py::cast(T{});
                for (const auto& item : d) py::setattr(self, item.first, item.second);
                return self.cast<T>();
            }));
        return cls_;
    }

private:
    py::class_<T> cls_;
    std::string name_;
    std::vector<std::string> fields_;
};

/// Area binders, one file each.
void bind_errors(py::module_& m);
void bind_io(py::module_& m);
void bind_detection(py::module_& m);
void bind_preprocess(py::module_& m);
void bind_recognition(py::module_& m);
void bind_video(py::module_& m);
void bind_social(py::module_& m);

}  // namespace facesocial::python
