// Reading images from disk with clear errors, and the list of image files in a folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace facesocial {

/// How load_image() returns the pixels.
enum class ImageColor {
    Bgr,   ///< 8-bit, 3 channels (grey files are expanded)
    Grey,  ///< 8-bit, 1 channel (colour files are converted)
    Any,   ///< 8-bit, 1 or 3 channels, as stored
};

/// Reads an image file. Throws FileError when the file is missing, unreadable or not an image
/// OpenCV can decode (the message says which).
cv::Mat load_image(const std::filesystem::path& path, ImageColor color = ImageColor::Bgr);

/// True when the file name has an image extension OpenCV reads (jpg, jpeg, png, pgm, ppm, bmp,
/// tif, tiff, webp), case-insensitive.
bool has_image_extension(const std::filesystem::path& path);

/// The image files directly inside `folder`, sorted by name (natural order: "2.pgm" before
/// "10.pgm"). Throws FileError when `folder` is not a readable directory.
std::vector<std::filesystem::path> list_images(const std::filesystem::path& folder);

/// Writes an image; the parent folder must exist. Throws FileError on failure.
void save_image(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace facesocial
