// Shared helpers of the tests: the data root and temporary folders.
#pragma once

#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "facesocial/datasets.hpp"

namespace facesocial::test {

/// The data root; the tests need real faces, so a missing root is a failure, not a skip.
inline std::filesystem::path data() {
    try {
        return data_root();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "real face sets are needed: " << e.what();
        throw;
    }
}

/// A fresh temporary folder removed when the object dies.
class TempDir {
public:
    TempDir() {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / ("facesocial_test_" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

}  // namespace facesocial::test
