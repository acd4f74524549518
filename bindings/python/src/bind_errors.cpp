// The library's exceptions as Python exceptions: std::invalid_argument is ValueError (pybind11's
// own translation); FileError is facesocial.FileError, an OSError; ModelFormatError is
// facesocial.ModelFormatError, a FileError.
#include "common.hpp"
#include "facesocial/error.hpp"

namespace facesocial::python {

namespace {

/// Raises `type`(message) with `path` set to the file concerned. (OSError's own `filename`
/// would turn the message into "[Errno None] None: path".)
void raise(const py::handle& type, const FileError& e) {
    py::object err = py::reinterpret_borrow<py::object>(type)(e.what());
    err.attr("path") = e.path();
    PyErr_SetObject(type.ptr(), err.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
    // pybind11 tries translators newest first, so the subclass is registered after its base.
    static py::exception<FileError> file_error(m, "FileError", PyExc_OSError);
    file_error.doc() = "A file could not be found, read, decoded or written (an OSError).";
    static py::exception<ModelFormatError> format_error(m, "ModelFormatError", file_error.ptr());
    format_error.doc() = "A model or bank file is truncated, corrupt, foreign or of a newer version.";
    file_error.attr("__module__") = "facesocial";
    format_error.attr("__module__") = "facesocial";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const ModelFormatError& e) {
            raise(format_error, e);
        } catch (const FileError& e) {
            raise(file_error, e);
        }
    });
}

}  // namespace facesocial::python
