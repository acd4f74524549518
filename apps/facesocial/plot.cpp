#include "plot.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <opencv2/imgproc.hpp>

#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::cli {

void write_csv(const std::filesystem::path& path, const Chart& chart) {
    std::ofstream out(path);
    if (!out) throw FileError(path.string(), "cannot write the CSV file");
    out << chart.x_label;
    for (const Series& s : chart.series) out << ',' << s.label;
    out << '\n';
    for (std::size_t i = 0; i < chart.x.size(); ++i) {
        out << chart.x[i];
        for (const Series& s : chart.series) {
            out << ',';
            if (i < s.y.size() && std::isfinite(s.y[i])) out << s.y[i];
        }
        out << '\n';
    }
    if (!out) throw FileError(path.string(), "writing the CSV file failed");
}

namespace {

std::string tick_label(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

}  // namespace

void write_png(const std::filesystem::path& path, const Chart& chart) {
    const int W = 900, H = 520, left = 80, right = 240, top = 70, bottom = 60;
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    const int pw = W - left - right, ph = H - top - bottom;
    double x_min = chart.x.empty() ? 0 : chart.x.front(), x_max = chart.x.empty() ? 1 : chart.x.back();
    for (double v : chart.x) x_min = std::min(x_min, v), x_max = std::max(x_max, v);
    if (x_max <= x_min) x_max = x_min + 1;
    const double y_min = chart.y_min, y_max = chart.y_max > chart.y_min ? chart.y_max : chart.y_min + 1;
    auto px = [&](double x) { return left + int(std::lround((x - x_min) / (x_max - x_min) * pw)); };
    auto py = [&](double y) {
        y = std::clamp(y, y_min, y_max);
        return top + ph - int(std::lround((y - y_min) / (y_max - y_min) * ph));
    };
    const cv::Scalar black(0, 0, 0), grid(225, 225, 225);
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    for (int i = 0; i <= 5; ++i) {
        const double yv = y_min + (y_max - y_min) * i / 5, xv = x_min + (x_max - x_min) * i / 5;
        cv::line(img, {left, py(yv)}, {left + pw, py(yv)}, grid, 1);
        cv::line(img, {px(xv), top}, {px(xv), top + ph}, grid, 1);
        cv::putText(img, tick_label(std::round(yv * 1000) / 1000), {8, py(yv) + 5}, font, 0.45, black, 1, cv::LINE_AA);
        cv::putText(img, tick_label(std::round(xv * 1000) / 1000), {px(xv) - 12, top + ph + 20}, font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    cv::rectangle(img, {left, top}, {left + pw, top + ph}, black, 1);
    cv::putText(img, chart.title, {left, 28}, font, 0.6, black, 1, cv::LINE_AA);
    cv::putText(img, chart.x_label, {left + pw / 2 - 60, H - 15}, font, 0.5, black, 1, cv::LINE_AA);
    cv::putText(img, chart.y_label, {8, top - 14}, font, 0.45, black, 1, cv::LINE_AA);
    const std::vector<cv::Scalar> colours{{200, 80, 30}, {40, 40, 220}, {40, 160, 40}, {160, 40, 160},
                                          {30, 160, 220}, {120, 120, 120}, {0, 0, 0}, {200, 160, 0}};
    for (std::size_t k = 0; k < chart.series.size(); ++k) {
        const Series& s = chart.series[k];
        const cv::Scalar c = colours[k % colours.size()];
        const bool dashed = k >= colours.size();
        cv::Point prev(-1, -1);
        for (std::size_t i = 0; i < chart.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.y[i])) {
                prev = {-1, -1};
                continue;
            }
            const cv::Point p(px(chart.x[i]), py(s.y[i]));
            if (prev.x >= 0 && !(dashed && i % 2)) cv::line(img, prev, p, c, 2, cv::LINE_AA);
            if (chart.x.size() <= 30) cv::circle(img, p, 3, c, cv::FILLED, cv::LINE_AA);
            prev = p;
        }
        const int ly = top + 10 + int(k) * 22;
        cv::line(img, {left + pw + 12, ly}, {left + pw + 40, ly}, c, 2, cv::LINE_AA);
        cv::putText(img, s.label, {left + pw + 46, ly + 5}, font, 0.42, black, 1, cv::LINE_AA);
    }
    save_image(path, img);
}

}  // namespace facesocial::cli
