#include "facesocial/observations.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "checks.hpp"

namespace facesocial {

void ObservationParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, const std::string& got) {
        throw std::invalid_argument("ObservationParams: expected " + field + " " + expected + ", got " + got);
    };
    if (face_size.width < 16 || face_size.height < 16) bad("face_size", "at least 16x16", detail::size_string(face_size));
    if (block_size < 2 || block_size > std::min(face_size.width, face_size.height))
        bad("block_size", "in [2, min(face_size)]", std::to_string(block_size));
    if (block_step < 1 || block_step > block_size) bad("block_step", "in [1, block_size]", std::to_string(block_step));
    if (coefficients < 1 || coefficients > block_size)
        bad("coefficients", "in [1, block_size]", std::to_string(coefficients));
    if (dimension() < 1) bad("coefficients", "at least 2 when drop_dc", std::to_string(coefficients));
}

cv::Size ObservationParams::grid() const {
    return {(face_size.width - block_size) / block_step + 1, (face_size.height - block_size) / block_step + 1};
}

Observations extract_observations(const cv::Mat& face, const ObservationParams& params) {
    params.validate();
    if (face.empty()) detail::fail("extract_observations", "a non-empty single-channel face", "an empty image");
    if (face.channels() != 1 || (face.depth() != CV_8U && face.depth() != CV_32F))
        detail::fail("extract_observations", "an 8-bit or float single-channel face", detail::type_name(face.type()));
    if (face.cols < 16 || face.rows < 16)
        detail::fail("extract_observations", "a face of at least 16x16 pixels", detail::size_string(face.size()));

    cv::Mat img;
    face.convertTo(img, CV_32F);
    if (img.size() != params.face_size) {
        cv::Mat resized;
        cv::resize(img, resized, params.face_size, 0, 0, img.cols > params.face_size.width ? cv::INTER_AREA : cv::INTER_LINEAR);
        img = resized;
    }
    const int B = params.block_size, S = params.block_step, K = params.coefficients;
    const cv::Size grid = params.grid();

    // The first K rows of the B-point orthonormal DCT-II matrix.
    std::vector<float> dct(std::size_t(K) * B);
    for (int u = 0; u < K; ++u) {
        const double alpha = u == 0 ? std::sqrt(1.0 / B) : std::sqrt(2.0 / B);
        for (int x = 0; x < B; ++x) dct[u * B + x] = float(alpha * std::cos(M_PI * (2 * x + 1) * u / (2.0 * B)));
    }

    // Pass 1, horizontal: for every image row and block column, the K horizontal frequencies.
    const int H = img.rows;
    std::vector<float> horiz(std::size_t(H) * grid.width * K);
    for (int y = 0; y < H; ++y) {
        const float* p = img.ptr<float>(y);
        float* out = &horiz[std::size_t(y) * grid.width * K];
        for (int c = 0; c < grid.width; ++c) {
            const float* block = p + c * S;
            for (int v = 0; v < K; ++v) {
                const float* d = &dct[v * B];
                float acc = 0.f;
                for (int x = 0; x < B; ++x) acc += d[x] * block[x];
                out[c * K + v] = acc;
            }
        }
    }

    // Pass 2, vertical: for every block, the K x K low frequencies.
    Observations obs;
    obs.grid = grid;
    const int dim = params.dimension();
    obs.vectors.create(grid.area(), dim, CV_32F);
    std::vector<float> coef(std::size_t(K) * K);
    for (int r = 0; r < grid.height; ++r) {
        for (int c = 0; c < grid.width; ++c) {
            std::fill(coef.begin(), coef.end(), 0.f);
            for (int y = 0; y < B; ++y) {
                const float* h = &horiz[(std::size_t(r * S + y) * grid.width + c) * K];
                for (int u = 0; u < K; ++u) {
                    const float du = dct[u * B + y];
                    for (int v = 0; v < K; ++v) coef[u * K + v] += du * h[v];
                }
            }
            float* out = obs.vectors.ptr<float>(r * grid.width + c);
            int j = 0;
            for (int i = params.drop_dc ? 1 : 0; i < K * K; ++i) out[j++] = coef[i];
        }
    }
    return obs;
}

}  // namespace facesocial
