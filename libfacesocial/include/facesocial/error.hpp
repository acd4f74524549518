// Project exception types.
//
// Contract used everywhere in the library:
//  - a caller mistake (wrong image type, bad parameter, box outside the image) throws
//    std::invalid_argument with a message "function: expected ..., got ...";
//  - a problem with a file (missing, unreadable, not an image, cannot be written) throws FileError;
//  - a model file that is truncated, corrupt, foreign or of an unknown version throws
//    ModelFormatError (a FileError).
#pragma once

#include <stdexcept>
#include <string>

namespace facesocial {

/// A file could not be found, read, decoded or written.
class FileError : public std::runtime_error {
public:
    FileError(const std::string& path, const std::string& what)
        : std::runtime_error(path + ": " + what), path_(path) {}
    /// The path of the file concerned.
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
};

/// A model or bank file is truncated, corrupt, of a foreign format or an unsupported version.
class ModelFormatError : public FileError {
public:
    using FileError::FileError;
};

}  // namespace facesocial
