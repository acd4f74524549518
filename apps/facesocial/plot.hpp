// Curves of the evaluations as CSV files and PNG line charts (drawn with OpenCV, so no plotting
// package is needed).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace facesocial::cli {

struct Series {
    std::string label;
    std::vector<double> y;  ///< one value per x; NaN = no point
};

struct Chart {
    std::string title, x_label, y_label;
    std::vector<double> x;
    std::vector<Series> series;
    double y_min = 0, y_max = 1;  ///< y range (values are clipped)
};

/// Writes x and every series as columns ("x_label,label1,label2,...").
void write_csv(const std::filesystem::path& path, const Chart& chart);
/// Draws the chart (900x520, axes, ticks, legend) and writes it as PNG.
void write_png(const std::filesystem::path& path, const Chart& chart);

}  // namespace facesocial::cli
