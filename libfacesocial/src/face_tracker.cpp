#include "facesocial/face_tracker.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "facesocial/detection.hpp"

namespace facesocial {

void TrackerParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, double got) {
        throw std::invalid_argument("TrackerParams: expected " + field + " " + expected + ", got " + std::to_string(got));
    };
    if (!(min_iou >= 0 && min_iou <= 1)) bad("min_iou", "in [0, 1]", min_iou);
    if (!(max_center_distance >= 0 && max_center_distance <= 10)) bad("max_center_distance", "in [0, 10]", max_center_distance);
    if (!(appearance_weight >= 0 && appearance_weight <= 100)) bad("appearance_weight", "in [0, 100]", appearance_weight);
    if (max_missed < 0 || max_missed > 100000) bad("max_missed", "in [0, 100000]", max_missed);
    if (!(velocity_smoothing >= 0 && velocity_smoothing < 1)) bad("velocity_smoothing", "in [0, 1)", velocity_smoothing);
    if (!(appearance_smoothing >= 0 && appearance_smoothing < 1))
        bad("appearance_smoothing", "in [0, 1)", appearance_smoothing);
}

// ---------------------------------------------------------------------------------------------
// Hungarian algorithm (shortest augmenting paths with row / column potentials), O(n^2 m) for
// n rows <= m columns.

std::vector<int> assign_min_cost(const cv::Mat& cost_in, double forbidden) {
    if (cost_in.empty()) return std::vector<int>(std::size_t(cost_in.rows), -1);
    if (cost_in.type() != CV_64FC1)
        throw std::invalid_argument("assign_min_cost: expected a CV_64FC1 cost matrix, got type " +
                                    std::to_string(cost_in.type()));
    const bool transposed = cost_in.rows > cost_in.cols;
    const cv::Mat cost = transposed ? cv::Mat(cost_in.t()) : cost_in;
    const int n = cost.rows, m = cost.cols;
    const double inf = std::numeric_limits<double>::infinity();
    auto c = [&](int i, int j) {
        const double v = cost.at<double>(i, j);
        return std::isfinite(v) ? std::min(v, forbidden) : forbidden;
    };
    // 1-based arrays: p[j] = row matched to column j (0 = none).
    std::vector<double> u(n + 1, 0), v(m + 1, 0);
    std::vector<int> p(m + 1, 0), way(m + 1, 0);
    for (int i = 1; i <= n; ++i) {
        p[0] = i;
        int j0 = 0;
        std::vector<double> minv(m + 1, inf);
        std::vector<char> used(m + 1, 0);
        do {
            used[j0] = 1;
            const int i0 = p[j0];
            double delta = inf;
            int j1 = 0;
            for (int j = 1; j <= m; ++j) {
                if (used[j]) continue;
                const double cur = c(i0 - 1, j - 1) - u[i0] - v[j];
                if (cur < minv[j]) minv[j] = cur, way[j] = j0;
                if (minv[j] < delta) delta = minv[j], j1 = j;
            }
            for (int j = 0; j <= m; ++j) {
                if (used[j])
                    u[p[j]] += delta, v[j] -= delta;
                else
                    minv[j] -= delta;
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            const int j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    std::vector<int> row_to_col(std::size_t(n), -1);
    for (int j = 1; j <= m; ++j)
        if (p[j] && c(p[j] - 1, j - 1) < forbidden) row_to_col[std::size_t(p[j] - 1)] = j - 1;
    if (!transposed) return row_to_col;
    std::vector<int> out(std::size_t(cost_in.rows), -1);
    for (int i = 0; i < n; ++i)
        if (row_to_col[std::size_t(i)] >= 0) out[std::size_t(row_to_col[std::size_t(i)])] = i;
    return out;
}

// ---------------------------------------------------------------------------------------------

cv::Mat appearance_signature(const cv::Mat& face) {
    if (face.empty() || face.channels() != 1 || (face.depth() != CV_8U && face.depth() != CV_32F))
        throw std::invalid_argument("appearance_signature: expected a single-channel 8-bit or float image, got " +
                                    (face.empty() ? std::string("an empty image") : "type " + std::to_string(face.type())));
    cv::Mat small;
    cv::resize(face, small, cv::Size(12, 14), 0, 0, cv::INTER_AREA);
    small.convertTo(small, CV_32F);
    small = small.reshape(1, 1).clone();
    small -= cv::mean(small)[0];
    const double norm = cv::norm(small);
    if (norm > 1e-9) small /= norm;
    return small;
}

namespace {

cv::Point2f centre(const cv::Rect2f& r) { return {r.x + r.width / 2, r.y + r.height / 2}; }

cv::Rect shifted(const cv::Rect& r, cv::Point2f d) {
    return {int(std::lround(r.x + d.x)), int(std::lround(r.y + d.y)), r.width, r.height};
}

double appearance_distance(const cv::Mat& a, const cv::Mat& b) {
    if (a.empty() || b.empty()) return -1;
    return 1.0 - a.dot(b);
}

cv::Mat blend(const cv::Mat& previous, const cv::Mat& measured, double keep) {
    if (previous.empty()) return measured.clone();
    if (measured.empty()) return previous;
    cv::Mat out = (1.0 - keep) * measured + keep * previous;
    const double norm = cv::norm(out);
    if (norm > 1e-9) out /= norm;
    return out;
}

}  // namespace

FaceTracker::FaceTracker(const TrackerParams& params) : params_(params) { params_.validate(); }

void FaceTracker::set_params(const TrackerParams& params) {
    params.validate();
    params_ = params;
}

void FaceTracker::reset() { tracks_.clear(); }

TrackerUpdate FaceTracker::update(const std::vector<TrackerInput>& faces) {
    int signature_length = -1;
    for (const TrackerInput& f : faces) {
        if (f.box.width <= 0 || f.box.height <= 0)
            throw std::invalid_argument("FaceTracker::update: expected non-empty face boxes, got " +
                                        std::to_string(f.box.width) + "x" + std::to_string(f.box.height));
        if (!f.appearance.empty()) {
            if (f.appearance.type() != CV_32FC1 || f.appearance.rows != 1)
                throw std::invalid_argument("FaceTracker::update: expected appearance signatures of one CV_32F row");
            if (signature_length >= 0 && f.appearance.cols != signature_length)
                throw std::invalid_argument("FaceTracker::update: expected appearance signatures of one length, got " +
                                            std::to_string(signature_length) + " and " + std::to_string(f.appearance.cols));
            signature_length = f.appearance.cols;
        }
    }

    const int T = int(tracks_.size()), D = int(faces.size());
    constexpr double kForbidden = 1e6;
    cv::Mat cost(T, D, CV_64F, cv::Scalar(kForbidden));
    for (int t = 0; t < T; ++t) {
        const Track& tr = tracks_[std::size_t(t)];
        const cv::Rect predicted = shifted(tr.box, tr.velocity);
        const cv::Point2f pc = centre(cv::Rect2f(predicted));
        for (int d = 0; d < D; ++d) {
            const cv::Rect& box = faces[std::size_t(d)].box;
            const double overlap = iou(predicted, box);
            const double dist = cv::norm(centre(cv::Rect2f(box)) - pc) / std::max(1, predicted.width);
            if (overlap < params_.min_iou && dist > params_.max_center_distance) continue;
            double c = (1.0 - overlap) + dist;
            const bool same_length = tr.appearance.cols == faces[std::size_t(d)].appearance.cols;
            const double a = same_length ? appearance_distance(tr.appearance, faces[std::size_t(d)].appearance) : -1;
            if (a >= 0) c += params_.appearance_weight * a;
            cost.at<double>(t, d) = c;
        }
    }
    const std::vector<int> match = assign_min_cost(cost, kForbidden);

    TrackerUpdate out;
    out.track_of.assign(std::size_t(D), 0);
    std::vector<char> taken(std::size_t(D), 0);
    std::vector<Track> kept;
    for (int t = 0; t < T; ++t) {
        Track tr = tracks_[std::size_t(t)];
        ++tr.age;
        const int d = match[std::size_t(t)];
        if (d >= 0) {
            const TrackerInput& f = faces[std::size_t(d)];
            const cv::Point2f step = (centre(cv::Rect2f(f.box)) - centre(cv::Rect2f(tr.box))) / float(tr.missed + 1);
            const float keep = float(params_.velocity_smoothing);
            tr.velocity = tr.hits > 1 ? (1 - keep) * step + keep * tr.velocity : step;
            tr.box = f.box;
            tr.appearance = blend(tr.appearance, f.appearance, params_.appearance_smoothing);
            ++tr.hits;
            tr.missed = 0;
            taken[std::size_t(d)] = 1;
            out.track_of[std::size_t(d)] = tr.id;
        } else {
            ++tr.missed;
            tr.box = shifted(tr.box, tr.velocity);
            if (tr.missed > params_.max_missed) {
                out.ended.push_back(tr.id);
                continue;
            }
        }
        kept.push_back(std::move(tr));
    }
    for (int d = 0; d < D; ++d) {
        if (taken[std::size_t(d)]) continue;
        Track tr;
        tr.id = next_id_++;
        tr.box = faces[std::size_t(d)].box;
        tr.age = 1;
        tr.hits = 1;
        tr.appearance = faces[std::size_t(d)].appearance.clone();
        out.track_of[std::size_t(d)] = tr.id;
        out.started.push_back(tr.id);
        kept.push_back(std::move(tr));
    }
    tracks_ = std::move(kept);
    return out;
}

}  // namespace facesocial
