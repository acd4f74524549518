#include "facesocial/ehmm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <istream>
#include <limits>
#include <numeric>
#include <ostream>
#include <stdexcept>

#include "binary_io.hpp"
#include "checks.hpp"
#include "ehmm_impl.hpp"
#include "parallel.hpp"
#include "facesocial/error.hpp"

namespace facesocial {

namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();
constexpr double kLog2Pi = 1.8378770664093453;
constexpr float kMinWeight = 1e-4f;

float clamp_log(double p, double min_p) { return float(std::log(std::clamp(p, min_p, 1.0 - min_p))); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Params

int EhmmParams::total_states() const { return std::accumulate(states.begin(), states.end(), 0); }

void EhmmParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, const std::string& got) {
        throw std::invalid_argument("EhmmParams: expected " + field + " " + expected + ", got " + got);
    };
    observations.validate();
    if (states.empty()) bad("states", "at least one super-state", "none");
    const cv::Size grid = observations.grid();
    int widest = 0;
    for (int n : states) {
        if (n < 1) bad("states", "every super-state with >= 1 embedded state", std::to_string(n));
        widest = std::max(widest, n);
    }
    if (int(states.size()) > grid.height)
        bad("states", "at most as many super-states as block rows (" + std::to_string(grid.height) + ")",
            std::to_string(states.size()));
    if (widest > grid.width)
        bad("states", "at most as many embedded states as block columns (" + std::to_string(grid.width) + ")",
            std::to_string(widest));
    if (mixtures < 1 || mixtures > 64) bad("mixtures", "in [1, 64]", std::to_string(mixtures));
    if (max_iterations < 0 || max_iterations > 1000) bad("max_iterations", "in [0, 1000]", std::to_string(max_iterations));
    if (!(tolerance >= 0)) bad("tolerance", ">= 0", std::to_string(tolerance));
    if (!(variance_floor > 0 && variance_floor < 1)) bad("variance_floor", "in (0, 1)", std::to_string(variance_floor));
    if (!(min_transition > 0 && min_transition < 0.5)) bad("min_transition", "in (0, 0.5)", std::to_string(min_transition));
    if (band_margin < -1 || band_margin > 1000) bad("band_margin", "in [-1, 1000]", std::to_string(band_margin));
}

// ---------------------------------------------------------------------------------------------
// Impl

void EmbeddedHmm::Impl::set_topology(const EhmmParams& p) {
    params = p;
    dim = p.observations.dimension();
    S = int(p.states.size());
    T = p.total_states();
    M = p.mixtures;
    first.assign(S + 1, 0);
    for (int s = 0; s < S; ++s) first[s + 1] = first[s] + p.states[s];
    mean = Eigen::MatrixXf::Zero(T * M, dim);
    var = Eigen::MatrixXf::Ones(T * M, dim);
    weight = Eigen::VectorXf::Constant(T * M, 1.0f / M);
    log_self.assign(T, std::log(0.5f));
    log_next.assign(T, std::log(0.5f));
    super_log_self.assign(S, std::log(0.5f));
    super_log_next.assign(S, std::log(0.5f));
    band_first.assign(S, 0);
    band_last.assign(S, p.observations.grid().height - 1);
}

void EmbeddedHmm::Impl::build_emission_weights() {
    super_of.assign(T, 0);
    for (int s = 0; s < S; ++s)
        for (int t = first[s]; t < first[s + 1]; ++t) super_of[t] = s;
    log_enter.assign(T, kNegInf);
    for (int s = 0; s < S; ++s)
        for (int t = first[s] + 1; t < first[s + 1]; ++t) log_enter[t] = log_next[t - 1];
    const int K = T * M;
    W.resize(2 * dim + 1, K);
    for (int k = 0; k < K; ++k) {
        // Parameters are stored state-major (k = t*M + m). W's columns are grouped by
        // super-state (each a slab of n_s*M columns, so a super-state's band of block rows is
        // one matrix product), mixture-major inside (m*n_s + i: the max over mixtures runs
        // over contiguous runs).
        const int t = k / M, s = super_of[t], n = first[s + 1] - first[s];
        const int col = first[s] * M + (k % M) * n + (t - first[s]);
        double c = std::log(std::max(weight(k), kMinWeight)) - 0.5 * dim * kLog2Pi;
        for (int j = 0; j < dim; ++j) {
            const double iv = 1.0 / var(k, j);
            W(j, col) = float(-0.5 * iv);
            W(dim + j, col) = float(mean(k, j) * iv);
            c -= 0.5 * (std::log(var(k, j)) + double(mean(k, j)) * mean(k, j) * iv);
        }
        W(2 * dim, col) = float(c);
    }
}

void EmbeddedHmm::Impl::features(const Observations& obs, RowMatrixF& F) {
    const int n = obs.vectors.rows, d = obs.vectors.cols;
    F.resize(n, 2 * d + 1);
    for (int i = 0; i < n; ++i) {
        const float* x = obs.vectors.ptr<float>(i);
        float* f = F.row(i).data();
        for (int j = 0; j < d; ++j) {
            f[j] = x[j] * x[j];
            f[d + j] = x[j];
        }
        f[2 * d] = 1.f;
    }
}

void EmbeddedHmm::Impl::emissions(const RowMatrixF& F, RowMatrixF& E, std::vector<int>* best_mixture, bool banded) const {
    // Computed transposed: per super-state s, GT = W_s^T F_band^T holds one row per Gaussian
    // (m*n_s + i) over the blocks of the band, so the max over mixtures is an element-wise max
    // of whole rows, vectorised over blocks. F^T of the row-major F is a free view.
    thread_local RowMatrixF GT, ET;
    thread_local Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> BT;
    const cv::Size grid = params.observations.grid();
    const Eigen::Index N = F.rows(), C = grid.width;
    ET.setConstant(T, N, kNegInf);
    if (best_mixture) BT.setZero(T, N);
    const auto FT = F.transpose();
    for (int s = 0; s < S; ++s) {
        const int n = first[s + 1] - first[s];
        const Eigen::Index b0 = banded ? band_first[s] * C : 0, b1 = banded ? (band_last[s] + 1) * C : N, w = b1 - b0;
        GT.resize(Eigen::Index(n) * M, w);
        GT.noalias() = W.middleCols(Eigen::Index(first[s]) * M, Eigen::Index(n) * M).transpose() * FT.middleCols(b0, w);
        for (int i = 0; i < n; ++i) {
            float* __restrict e = ET.row(first[s] + i).data() + b0;
            std::copy_n(GT.row(i).data(), w, e);
            int* __restrict arg = best_mixture ? BT.row(first[s] + i).data() + b0 : nullptr;
            for (int m = 1; m < M; ++m) {
                const float* __restrict g = GT.row(Eigen::Index(m) * n + i).data();
                if (arg) {
                    for (Eigen::Index b = 0; b < w; ++b) {
                        const bool better = g[b] > e[b];
                        e[b] = better ? g[b] : e[b];
                        arg[b] = better ? m : arg[b];
                    }
                } else {
                    for (Eigen::Index b = 0; b < w; ++b) e[b] = std::max(e[b], g[b]);
                }
            }
        }
    }
    E = ET.transpose();
    if (best_mixture) {
        best_mixture->resize(std::size_t(N) * T);
        Eigen::Map<Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(best_mixture->data(), N, T) = BT.transpose();
    }
}

double EmbeddedHmm::Impl::viterbi(const RowMatrixF& E, cv::Size grid, EhmmSegmentation* seg) const {
    const int R = grid.height, C = grid.width, nT = T;
    // Row level: every block row against every super-state at once. The embedded states of all
    // super-states form one vector; entering a super-state's first state from the state before
    // it is impossible (log_enter = -inf), so the super-states do not mix and one vectorised
    // recurrence over the T states runs them all. L(r, s) is then the log-likelihood of row r
    // ending in the last state of super-state s.
    thread_local std::vector<float> L, cur, prev;
    L.resize(std::size_t(R) * S);
    cur.assign(nT + 1, kNegInf);  // index 0 is a -inf guard: "the state before the first"
    prev.assign(nT + 1, kNegInf);
    std::vector<uint8_t> advanced;  // back pointers of one row: C x T, 1 = came from t - 1
    std::vector<int> row_paths;     // per (row, super-state): the C embedded states
    if (seg) {
        advanced.assign(std::size_t(C) * nT, 0);
        row_paths.assign(std::size_t(R) * S * C, 0);
    }
    const float* __restrict ls = log_self.data();
    const float* __restrict le = log_enter.data();
    for (int r = 0; r < R; ++r) {
        float* d = cur.data() + 1;
        float* p = prev.data() + 1;
        const float* e0 = E.row(r * C).data();
        std::fill_n(d, nT, kNegInf);
        for (int s = 0; s < S; ++s) d[first[s]] = e0[first[s]];
        for (int c = 1; c < C; ++c) {
            std::swap(d, p);
            const float* __restrict e = E.row(r * C + c).data();
            float* __restrict out = d;
            const float* __restrict in = p;
            if (seg) {
                uint8_t* __restrict a = &advanced[std::size_t(c) * nT];
                for (int t = 0; t < nT; ++t) {
                    const float stay = in[t] + ls[t], adv = in[t - 1] + le[t];
                    a[t] = adv > stay;
                    out[t] = std::max(stay, adv) + e[t];
                }
            } else {
                for (int t = 0; t < nT; ++t) out[t] = std::max(in[t] + ls[t], in[t - 1] + le[t]) + e[t];
            }
        }
        for (int s = 0; s < S; ++s) L[std::size_t(r) * S + s] = d[first[s + 1] - 1];
        if (seg) {
            for (int s = 0; s < S; ++s) {
                int* path = &row_paths[(std::size_t(r) * S + s) * C];
                int t = first[s + 1] - 1;
                for (int c = C - 1; c >= 0; --c) {
                    path[c] = t - first[s];
                    if (c > 0 && advanced[std::size_t(c) * nT + t]) --t;
                }
            }
        }
    }
    // Super level over rows.
    std::vector<double> phi(S, -std::numeric_limits<double>::infinity());
    std::vector<uint8_t> super_adv(seg ? std::size_t(R) * S : 0, 0);
    phi[0] = L[0];
    for (int r = 1; r < R; ++r) {
        for (int s = S - 1; s >= 0; --s) {
            const double stay = phi[s] + super_log_self[s];
            const double adv = s > 0 ? phi[s - 1] + super_log_next[s - 1] : -std::numeric_limits<double>::infinity();
            const bool a = adv > stay;
            if (seg) super_adv[std::size_t(r) * S + s] = a;
            phi[s] = (a ? adv : stay) + L[std::size_t(r) * S + s];
        }
    }
    const double total = phi[S - 1];
    if (seg) {
        seg->grid = grid;
        seg->log_likelihood = total;
        seg->super_state.assign(R, 0);
        seg->state.assign(std::size_t(R) * C, 0);
        int s = S - 1;
        for (int r = R - 1; r >= 0; --r) {
            seg->super_state[r] = s;
            std::copy_n(&row_paths[(std::size_t(r) * S + s) * C], C, &seg->state[std::size_t(r) * C]);
            if (r > 0 && super_adv[std::size_t(r) * S + s]) --s;
        }
    }
    return total;
}

// ---------------------------------------------------------------------------------------------
// Training

namespace {

/// Deterministic k-means: farthest-first seeds (the first is the row farthest from the mean,
/// each next one the row farthest from the seeds so far), then Lloyd iterations. Returns the
/// cluster of each row. Seeds spread over the data keep two mixtures from starting inside one
/// cluster, which hard (Viterbi) re-estimation could not undo.
std::vector<int> kmeans(const Eigen::MatrixXf& X, int k) {
    const Eigen::Index n = X.rows();
    std::vector<int> label(n, 0);
    if (n == 0 || k <= 1) return label;
    Eigen::MatrixXf centers(k, X.cols());
    Eigen::VectorXf nearest = (X.rowwise() - X.colwise().mean()).rowwise().squaredNorm();
    for (int j = 0; j < k; ++j) {
        Eigen::Index far;
        nearest.maxCoeff(&far);
        centers.row(j) = X.row(far);
        nearest = nearest.cwiseMin((X.rowwise() - centers.row(j)).rowwise().squaredNorm());
    }
    for (int iter = 0; iter < 10; ++iter) {
        bool changed = false;
        for (Eigen::Index i = 0; i < n; ++i) {
            Eigen::Index best;
            (centers.rowwise() - X.row(i)).rowwise().squaredNorm().minCoeff(&best);
            if (label[i] != int(best)) label[i] = int(best), changed = true;
        }
        Eigen::MatrixXf sum = Eigen::MatrixXf::Zero(k, X.cols());
        std::vector<int> count(k, 0);
        for (Eigen::Index i = 0; i < n; ++i) sum.row(label[i]) += X.row(i), ++count[label[i]];
        for (int j = 0; j < k; ++j)
            if (count[j] > 0) centers.row(j) = sum.row(j) / float(count[j]);
        if (!changed && iter > 0) break;
    }
    return label;
}

/// Sufficient statistics of the Gaussians and transitions under one hard assignment.
struct Stats {
    Eigen::MatrixXd sum, sum_sq;  // T*M x dim
    Eigen::VectorXd count;        // T*M
    std::vector<double> self, next, super_self, super_next;

    Stats(int K, int dim, int T, int S)
        : sum(Eigen::MatrixXd::Zero(K, dim)), sum_sq(Eigen::MatrixXd::Zero(K, dim)), count(Eigen::VectorXd::Zero(K)),
          self(T, 0), next(T, 0), super_self(S, 0), super_next(S, 0) {}

    void add(int k, const float* x, int dim) {
        count(k) += 1;
        for (int j = 0; j < dim; ++j) sum(k, j) += x[j], sum_sq(k, j) += double(x[j]) * x[j];
    }
};

/// Mixture assignment by k-means inside every embedded state: adds each state's vectors to the
/// statistics of its nearest cluster.
void cluster_states(const std::vector<std::vector<const float*>>& per_state, int mixtures, int dim, Stats& st) {
    for (std::size_t t = 0; t < per_state.size(); ++t) {
        Eigen::MatrixXf X(per_state[t].size(), dim);
        for (std::size_t i = 0; i < per_state[t].size(); ++i)
            X.row(Eigen::Index(i)) = Eigen::Map<const Eigen::RowVectorXf>(per_state[t][i], dim);
        const std::vector<int> label = kmeans(X, mixtures);
        for (std::size_t i = 0; i < per_state[t].size(); ++i)
            st.add(int(t) * mixtures + label[i], per_state[t][i], dim);
    }
}

void add_transitions(const EmbeddedHmm::Impl& m, const EhmmSegmentation& seg, Stats& st) {
    const int R = seg.grid.height, C = seg.grid.width;
    for (int r = 0; r < R; ++r) {
        const int s = seg.super_state[r];
        if (r > 0) (seg.super_state[r - 1] == s ? st.super_self : st.super_next)[seg.super_state[r - 1]] += 1;
        for (int c = 1; c < C; ++c) {
            const int prev = m.first[s] + seg.state[std::size_t(r) * C + c - 1];
            const int cur = m.first[s] + seg.state[std::size_t(r) * C + c];
            (prev == cur ? st.self : st.next)[prev] += 1;
        }
    }
}

void reestimate(EmbeddedHmm::Impl& m, const Stats& st, const Eigen::VectorXd& floor) {
    for (int t = 0; t < m.T; ++t) {
        double state_count = 0;
        for (int j = 0; j < m.M; ++j) state_count += st.count(t * m.M + j);
        for (int j = 0; j < m.M; ++j) {
            const int k = t * m.M + j;
            const double n = st.count(k);
            if (n > 0) {
                for (int d = 0; d < m.dim; ++d) {
                    const double mu = st.sum(k, d) / n;
                    m.mean(k, d) = float(mu);
                    m.var(k, d) = float(std::max(st.sum_sq(k, d) / n - mu * mu, floor(d)));
                }
            }  // an empty mixture keeps its Gaussian and gets the minimum weight
            m.weight(k) = float(state_count > 0 ? std::max(n / state_count, double(kMinWeight)) : 1.0 / m.M);
        }
        const float total = m.weight.segment(t * m.M, m.M).sum();
        m.weight.segment(t * m.M, m.M) /= total;
    }
    const double pmin = m.params.min_transition;
    for (int s = 0; s < m.S; ++s) {
        for (int t = m.first[s]; t < m.first[s + 1]; ++t) {
            if (t == m.first[s + 1] - 1) {  // last state of a row: it can only stay
                m.log_self[t] = 0.f;
                m.log_next[t] = kNegInf;
                continue;
            }
            const double p = (st.self[t] + 1.0) / (st.self[t] + st.next[t] + 2.0);
            m.log_self[t] = clamp_log(p, pmin);
            m.log_next[t] = clamp_log(1.0 - p, pmin);
        }
        if (s == m.S - 1) {
            m.super_log_self[s] = 0.f;
            m.super_log_next[s] = kNegInf;
        } else {
            const double p = (st.super_self[s] + 1.0) / (st.super_self[s] + st.super_next[s] + 2.0);
            m.super_log_self[s] = clamp_log(p, pmin);
            m.super_log_next[s] = clamp_log(1.0 - p, pmin);
        }
    }
    m.build_emission_weights();
}

void check_training_grids(const std::vector<Observations>& obs, const ObservationParams& params, const char* fn) {
    const cv::Size grid = params.grid();
    const int dim = params.dimension();
    for (const Observations& o : obs) {
        if (o.grid != grid || o.vectors.rows != grid.area() || o.vectors.cols != dim || o.vectors.type() != CV_32F)
            detail::fail(fn, "observation grids of " + detail::size_string(grid) + " blocks x " + std::to_string(dim) + " floats",
                         detail::size_string(o.grid) + " blocks x " + std::to_string(o.vectors.cols));
        if (!cv::checkRange(o.vectors)) detail::fail(fn, "finite observations", "NaN or infinity in an observation");
    }
}

/// Variance floor per dimension: `share` of the observations' own variance (at least 1e-6).
Eigen::VectorXd variance_floor(const std::vector<Observations>& obs, int dim, double share) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(dim), sum_sq = Eigen::VectorXd::Zero(dim);
    double n = 0;
    for (const Observations& o : obs)
        for (int i = 0; i < o.vectors.rows; ++i) {
            const float* x = o.vectors.ptr<float>(i);
            for (int d = 0; d < dim; ++d) sum(d) += x[d], sum_sq(d) += double(x[d]) * x[d];
            n += 1;
        }
    Eigen::VectorXd floor(dim);
    for (int d = 0; d < dim; ++d) {
        const double mu = sum(d) / n;
        floor(d) = std::max(share * (sum_sq(d) / n - mu * mu), 1e-6);
    }
    return floor;
}

/// MAP update of `m` from the statistics `st` with `prior` (the background) as the prior.
void map_update(EmbeddedHmm::Impl& m, const EmbeddedHmm::Impl& prior, const Stats& st, const Eigen::VectorXd& floor,
                const EhmmAdaptParams& ap) {
    const double r = ap.relevance;
    for (int t = 0; t < m.T; ++t) {
        double state_count = 0;
        for (int j = 0; j < m.M; ++j) state_count += st.count(t * m.M + j);
        for (int j = 0; j < m.M; ++j) {
            const int k = t * m.M + j;
            const double n = st.count(k), a = n / (n + r);
            for (int d = 0; d < m.dim; ++d) {
                const double x = n > 0 ? st.sum(k, d) / n : 0.0, x2 = n > 0 ? st.sum_sq(k, d) / n : 0.0;
                const double mu0 = prior.mean(k, d), var0 = prior.var(k, d);
                const double mu = a * x + (1 - a) * mu0;
                m.mean(k, d) = float(mu);
                m.var(k, d) = ap.adapt_variances ? float(std::max(a * x2 + (1 - a) * (var0 + mu0 * mu0) - mu * mu, floor(d)))
                                                 : float(var0);
            }
            const double w0 = prior.weight(k);
            m.weight(k) = float(std::max(ap.adapt_weights && state_count > 0 ? a * n / state_count + (1 - a) * w0 : w0,
                                         double(kMinWeight)));
        }
        const float total = m.weight.segment(t * m.M, m.M).sum();
        m.weight.segment(t * m.M, m.M) /= total;
    }
    if (ap.adapt_transitions) {
        const double pmin = m.params.min_transition;
        auto blend = [&](double self, double next, float log_self0) {
            return (self + r * std::exp(double(log_self0))) / (self + next + r);
        };
        for (int s = 0; s < m.S; ++s) {
            for (int t = m.first[s]; t < m.first[s + 1] - 1; ++t) {  // the last state of a row only stays
                const double p = blend(st.self[t], st.next[t], prior.log_self[t]);
                m.log_self[t] = clamp_log(p, pmin);
                m.log_next[t] = clamp_log(1.0 - p, pmin);
            }
            if (s < m.S - 1) {
                const double p = blend(st.super_self[s], st.super_next[s], prior.super_log_self[s]);
                m.super_log_self[s] = clamp_log(p, pmin);
                m.super_log_next[s] = clamp_log(1.0 - p, pmin);
            }
        }
    }
    m.build_emission_weights();
}

/// The Viterbi alignments of a training set under the current model.
struct Alignments {
    std::vector<EhmmSegmentation> segs;
    std::vector<std::vector<int>> best;  // per face: best mixture of every (block, state)
};

/// Aligns every face (in parallel for large sets: the background model trains on hundreds);
/// returns the summed log-likelihood. The statistics are then added in face order, so the
/// result does not depend on the number of threads.
double align_all(const EmbeddedHmm::Impl& m, const std::vector<RowMatrixF>& F, cv::Size grid, Alignments& al) {
    const std::size_t n = F.size();
    al.segs.resize(n);
    al.best.resize(n);
    std::vector<double> ll(n);
    auto one = [&](std::size_t i) {
        thread_local RowMatrixF E;
        m.emissions(F[i], E, &al.best[i]);
        ll[i] = m.viterbi(E, grid, &al.segs[i]);
    };
    constexpr std::size_t kParallelFrom = 16;
    detail::parallel_for(n, one, n >= kParallelFrom ? -1 : 1);
    return std::accumulate(ll.begin(), ll.end(), 0.0);
}

/// The block rows each super-state took in `segs`, widened by `margin` rows on each side.
void learn_bands(EmbeddedHmm::Impl& m, const std::vector<EhmmSegmentation>& segs, int margin) {
    if (segs.empty()) return;
    const int R = segs.front().grid.height;
    std::vector<int> lo(m.S, R), hi(m.S, -1);
    for (const EhmmSegmentation& seg : segs)
        for (int r = 0; r < R; ++r) {
            const int s = seg.super_state[r];
            lo[s] = std::min(lo[s], r);
            hi[s] = std::max(hi[s], r);
        }
    for (int s = 0; s < m.S; ++s) {
        m.band_first[s] = std::max(0, lo[s] - margin);
        m.band_last[s] = std::min(R - 1, hi[s] + margin);
    }
}

EhmmSegmentation uniform_segmentation(const EmbeddedHmm::Impl& m, cv::Size grid) {
    EhmmSegmentation seg;
    seg.grid = grid;
    seg.super_state.resize(grid.height);
    seg.state.resize(std::size_t(grid.area()));
    for (int r = 0; r < grid.height; ++r) {
        const int s = r * m.S / grid.height;
        seg.super_state[r] = s;
        const int n = m.first[s + 1] - m.first[s];
        for (int c = 0; c < grid.width; ++c) seg.state[std::size_t(r) * grid.width + c] = c * n / grid.width;
    }
    return seg;
}

}  // namespace

EmbeddedHmm EmbeddedHmm::train(const std::vector<cv::Mat>& faces, const EhmmParams& params, EhmmTrainingReport* report) {
    params.validate();
    if (faces.empty()) detail::fail("EmbeddedHmm::train", "at least one face", "none");
    std::vector<Observations> obs;
    obs.reserve(faces.size());
    for (const cv::Mat& f : faces) obs.push_back(extract_observations(f, params.observations));
    return train(obs, params, report);
}

EmbeddedHmm EmbeddedHmm::train(const std::vector<Observations>& obs, const EhmmParams& params,
                               EhmmTrainingReport* report) {
    params.validate();
    if (obs.empty()) detail::fail("EmbeddedHmm::train", "at least one observation grid", "none");
    const cv::Size grid = params.observations.grid();
    const int dim = params.observations.dimension();
    check_training_grids(obs, params.observations, "EmbeddedHmm::train");

    auto impl = std::make_shared<Impl>();
    Impl& m = *impl;
    m.set_topology(params);
    const int K = m.T * m.M;

    const double total_n = double(obs.size()) * grid.area();
    const Eigen::VectorXd floor = variance_floor(obs, dim, params.variance_floor);

    // Uniform segmentation, then k-means inside every state.
    std::vector<EhmmSegmentation> segs;
    for (std::size_t i = 0; i < obs.size(); ++i) segs.push_back(uniform_segmentation(m, grid));
    {
        std::vector<std::vector<const float*>> per_state(m.T);
        for (std::size_t i = 0; i < obs.size(); ++i)
            for (int b = 0; b < grid.area(); ++b) {
                const int r = b / grid.width;
                per_state[m.first[segs[i].super_state[r]] + segs[i].state[b]].push_back(obs[i].vectors.ptr<float>(b));
            }
        Stats st(K, dim, m.T, m.S);
        cluster_states(per_state, m.M, dim, st);
        for (const auto& s : segs) add_transitions(m, s, st);
        reestimate(m, st, floor);
    }

    // Viterbi re-estimation.
    EhmmTrainingReport local;
    EhmmTrainingReport& rep = report ? *report : local;
    rep = {};
    std::vector<RowMatrixF> F(obs.size());
    for (std::size_t i = 0; i < obs.size(); ++i) Impl::features(obs[i], F[i]);
    double previous = -std::numeric_limits<double>::infinity();
    Alignments al;
    for (int iter = 0; iter < params.max_iterations; ++iter) {
        Stats st(K, dim, m.T, m.S);
        const double ll = align_all(m, F, grid, al);
        const bool recluster = params.recluster_mixtures && iter == 1;
        std::vector<std::vector<const float*>> per_state(recluster ? m.T : 0);
        for (std::size_t i = 0; i < obs.size(); ++i) {
            const EhmmSegmentation& seg = al.segs[i];
            const std::vector<int>& best_mixture = al.best[i];
            for (int b = 0; b < grid.area(); ++b) {
                const int t = m.first[seg.super_state[b / grid.width]] + seg.state[b];
                if (recluster)
                    per_state[t].push_back(obs[i].vectors.ptr<float>(b));
                else
                    st.add(t * m.M + best_mixture[std::size_t(b) * m.T + t], obs[i].vectors.ptr<float>(b), dim);
            }
            add_transitions(m, seg, st);
        }
        if (recluster) cluster_states(per_state, m.M, dim, st);
        const double mean_ll = ll / (total_n);
        rep.mean_log_likelihood.push_back(mean_ll);
        rep.iterations = iter + 1;
        if (mean_ll - previous < params.tolerance) {
            rep.converged = true;
            break;
        }
        previous = mean_ll;
        reestimate(m, st, floor);
    }
    if (params.band_margin >= 0) {
        align_all(m, F, grid, al);
        learn_bands(m, al.segs, params.band_margin);
    }
    EmbeddedHmm out;
    out.impl_ = std::move(impl);
    return out;
}

void EhmmAdaptParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, const std::string& got) {
        throw std::invalid_argument("EhmmAdaptParams: expected " + field + " " + expected + ", got " + got);
    };
    if (!(relevance >= 0 && relevance <= 1e6)) bad("relevance", "in [0, 1e6]", std::to_string(relevance));
    if (iterations < 1 || iterations > 100) bad("iterations", "in [1, 100]", std::to_string(iterations));
}

EmbeddedHmm EmbeddedHmm::adapt(const EmbeddedHmm& background, const std::vector<cv::Mat>& faces,
                               const EhmmAdaptParams& params, EhmmTrainingReport* report) {
    if (background.empty()) detail::fail("EmbeddedHmm::adapt", "a trained background model", "an empty model");
    if (faces.empty()) detail::fail("EmbeddedHmm::adapt", "at least one face", "none");
    std::vector<Observations> obs;
    obs.reserve(faces.size());
    for (const cv::Mat& f : faces) obs.push_back(extract_observations(f, background.params().observations));
    return adapt(background, obs, params, report);
}

EmbeddedHmm EmbeddedHmm::adapt(const EmbeddedHmm& background, const std::vector<Observations>& obs,
                               const EhmmAdaptParams& params, EhmmTrainingReport* report) {
    params.validate();
    if (background.empty()) detail::fail("EmbeddedHmm::adapt", "a trained background model", "an empty model");
    if (obs.empty()) detail::fail("EmbeddedHmm::adapt", "at least one observation grid", "none");
    const Impl& prior = background.impl();
    check_training_grids(obs, prior.params.observations, "EmbeddedHmm::adapt");
    const cv::Size grid = prior.params.observations.grid();
    const Eigen::VectorXd floor = variance_floor(obs, prior.dim, prior.params.variance_floor);

    auto impl = std::make_shared<Impl>(prior);
    Impl& m = *impl;
    EhmmTrainingReport local;
    EhmmTrainingReport& rep = report ? *report : local;
    rep = {};
    std::vector<RowMatrixF> F(obs.size());
    for (std::size_t i = 0; i < obs.size(); ++i) Impl::features(obs[i], F[i]);
    Alignments al;
    for (int iter = 0; iter < params.iterations; ++iter) {
        Stats st(m.T * m.M, m.dim, m.T, m.S);
        const double ll = align_all(m, F, grid, al);
        for (std::size_t i = 0; i < obs.size(); ++i) {
            const EhmmSegmentation& seg = al.segs[i];
            const std::vector<int>& best_mixture = al.best[i];
            for (int b = 0; b < grid.area(); ++b) {
                const int t = m.first[seg.super_state[b / grid.width]] + seg.state[b];
                st.add(t * m.M + best_mixture[std::size_t(b) * m.T + t], obs[i].vectors.ptr<float>(b), m.dim);
            }
            add_transitions(m, seg, st);
        }
        rep.mean_log_likelihood.push_back(ll / (double(obs.size()) * grid.area()));
        rep.iterations = iter + 1;
        map_update(m, prior, st, floor, params);
    }
    rep.converged = true;  // a fixed number of rounds by design
    EmbeddedHmm out;
    out.impl_ = std::move(impl);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Scoring

EmbeddedHmm::EmbeddedHmm() = default;
EmbeddedHmm::~EmbeddedHmm() = default;
EmbeddedHmm::EmbeddedHmm(const EmbeddedHmm&) = default;
EmbeddedHmm& EmbeddedHmm::operator=(const EmbeddedHmm&) = default;
EmbeddedHmm::EmbeddedHmm(EmbeddedHmm&&) noexcept = default;
EmbeddedHmm& EmbeddedHmm::operator=(EmbeddedHmm&&) noexcept = default;

bool EmbeddedHmm::empty() const { return !impl_; }

const EmbeddedHmm::Impl& EmbeddedHmm::impl() const {
    if (!impl_) throw std::logic_error("EmbeddedHmm: the model is empty (train or read it first)");
    return *impl_;
}

const EhmmParams& EmbeddedHmm::params() const { return impl().params; }

double EmbeddedHmm::score(const cv::Mat& face) const { return score(extract_observations(face, impl().params.observations)); }

namespace {
void require_grid(const EmbeddedHmm::Impl& m, const Observations& o, const char* fn) {
    const cv::Size grid = m.params.observations.grid();
    if (o.grid != grid || o.vectors.rows != grid.area() || o.vectors.cols != m.dim || o.vectors.type() != CV_32F)
        detail::fail(fn, "observations of " + detail::size_string(grid) + " blocks x " + std::to_string(m.dim) + " floats",
                     detail::size_string(o.grid) + " blocks x " + std::to_string(o.vectors.cols));
}
}  // namespace

double EmbeddedHmm::score(const Observations& o) const {
    const Impl& m = impl();
    require_grid(m, o, "EmbeddedHmm::score");
    thread_local RowMatrixF F;
    Impl::features(o, F);
    return m.score_features(F, o.grid);
}

double EmbeddedHmm::Impl::score_features(const RowMatrixF& F, cv::Size grid) const {
    // Per-thread scratch: scoring runs per face and per person, and fresh buffers of this size
    // would go through mmap and page faults on every call.
    thread_local RowMatrixF E;
    emissions(F, E, nullptr, true);
    return viterbi(E, grid, nullptr) / double(grid.area());
}

EhmmSegmentation EmbeddedHmm::segment(const Observations& o) const {
    const Impl& m = impl();
    require_grid(m, o, "EmbeddedHmm::segment");
    RowMatrixF F, E;
    Impl::features(o, F);
    m.emissions(F, E, nullptr, true);
    EhmmSegmentation seg;
    m.viterbi(E, o.grid, &seg);
    return seg;
}

// ---------------------------------------------------------------------------------------------
// Sampling and random models

std::pair<Observations, EhmmSegmentation> EmbeddedHmm::sample(cv::Size grid, std::mt19937& rng) const {
    const Impl& m = impl();
    if (grid.height < m.S || grid.width < *std::max_element(m.params.states.begin(), m.params.states.end()))
        detail::fail("EmbeddedHmm::sample", "a grid with room for every state", detail::size_string(grid));
    // A uniformly random left-to-right path that visits every state: cut points among positions.
    auto random_path = [&](int length, int states) {
        std::vector<int> cuts(length - 1);
        std::iota(cuts.begin(), cuts.end(), 1);
        std::shuffle(cuts.begin(), cuts.end(), rng);
        cuts.resize(states - 1);
        std::sort(cuts.begin(), cuts.end());
        std::vector<int> path(length);
        int state = 0;
        for (int i = 0; i < length; ++i) {
            while (state < states - 1 && i >= cuts[state]) ++state;
            path[i] = state;
        }
        return path;
    };
    EhmmSegmentation seg;
    seg.grid = grid;
    seg.super_state = random_path(grid.height, m.S);
    seg.state.resize(std::size_t(grid.area()));
    Observations o;
    o.grid = grid;
    o.vectors.create(grid.area(), m.dim, CV_32F);
    std::normal_distribution<float> normal(0.f, 1.f);
    for (int r = 0; r < grid.height; ++r) {
        const int s = seg.super_state[r];
        const std::vector<int> path = random_path(grid.width, m.first[s + 1] - m.first[s]);
        for (int c = 0; c < grid.width; ++c) {
            const int b = r * grid.width + c;
            seg.state[b] = path[c];
            const int t = m.first[s] + path[c];
            std::discrete_distribution<int> pick(m.weight.data() + t * m.M, m.weight.data() + (t + 1) * m.M);
            const int k = t * m.M + pick(rng);
            float* x = o.vectors.ptr<float>(b);
            for (int d = 0; d < m.dim; ++d) x[d] = m.mean(k, d) + std::sqrt(m.var(k, d)) * normal(rng);
        }
    }
    return {o, seg};
}

EmbeddedHmm EmbeddedHmm::random(const EhmmParams& params, std::mt19937& rng, double spread) {
    params.validate();
    auto impl = std::make_shared<Impl>();
    impl->set_topology(params);
    std::normal_distribution<float> normal(0.f, float(spread));
    std::uniform_real_distribution<float> uni(0.5f, 1.5f);
    for (int k = 0; k < impl->T * impl->M; ++k)
        for (int d = 0; d < impl->dim; ++d) impl->mean(k, d) = normal(rng), impl->var(k, d) = uni(rng);
    impl->build_emission_weights();
    EmbeddedHmm out;
    out.impl_ = std::move(impl);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Serialisation

namespace {

using detail::get_bytes;
using detail::put;
using detail::put_bytes;
constexpr const char* kWhat = "embedded HMM";

template <class T>
T get(std::istream& in) {
    return detail::get<T>(in, kWhat);
}

void put_floats(std::ostream& out, const float* p, std::size_t n) { put_bytes(out, p, n * sizeof(float)); }
void get_floats(std::istream& in, float* p, std::size_t n) { get_bytes(in, p, n * sizeof(float), kWhat); }

}  // namespace

void write_ehmm_params(std::ostream& out, const EhmmParams& p) {
    put<int32_t>(out, p.observations.face_size.width);
    put<int32_t>(out, p.observations.face_size.height);
    put<int32_t>(out, p.observations.block_size);
    put<int32_t>(out, p.observations.block_step);
    put<int32_t>(out, p.observations.coefficients);
    put<int32_t>(out, p.observations.drop_dc ? 1 : 0);
    put<int32_t>(out, int32_t(p.states.size()));
    for (int n : p.states) put<int32_t>(out, n);
    put<int32_t>(out, p.mixtures);
    put<int32_t>(out, p.max_iterations);
    put<double>(out, p.tolerance);
    put<double>(out, p.variance_floor);
    put<double>(out, p.min_transition);
    put<uint8_t>(out, p.recluster_mixtures ? 1 : 0);  // since layout 2
    put<int32_t>(out, p.band_margin);                 // since layout 3
}

EhmmParams read_ehmm_params(std::istream& in, uint32_t layout) {
    if (layout < 1 || layout > EmbeddedHmm::kLayoutVersion)
        throw ModelFormatError("<stream>", "embedded HMM of layout version " + std::to_string(layout) +
                                               "; this library reads 1 to " + std::to_string(EmbeddedHmm::kLayoutVersion));
    EhmmParams p;
    p.observations.face_size.width = get<int32_t>(in);
    p.observations.face_size.height = get<int32_t>(in);
    p.observations.block_size = get<int32_t>(in);
    p.observations.block_step = get<int32_t>(in);
    p.observations.coefficients = get<int32_t>(in);
    p.observations.drop_dc = get<int32_t>(in) != 0;
    const int32_t S = get<int32_t>(in);
    if (S < 1 || S > 1000) throw ModelFormatError("<stream>", "embedded HMM with " + std::to_string(S) + " super-states");
    p.states.resize(S);
    for (auto& n : p.states) n = get<int32_t>(in);
    p.mixtures = get<int32_t>(in);
    p.max_iterations = get<int32_t>(in);
    p.tolerance = get<double>(in);
    p.variance_floor = get<double>(in);
    p.min_transition = get<double>(in);
    if (layout >= 2) p.recluster_mixtures = get<uint8_t>(in) != 0;
    p.band_margin = layout >= 3 ? get<int32_t>(in) : -1;  // older models scored every row
    try {
        p.validate();
    } catch (const std::invalid_argument& e) {
        throw ModelFormatError("<stream>", std::string("embedded HMM with invalid parameters: ") + e.what());
    }
    return p;
}

void EmbeddedHmm::write(std::ostream& out) const {
    const Impl& m = impl();
    const EhmmParams& p = m.params;
    write_ehmm_params(out, p);
    const std::size_t K = std::size_t(m.T) * m.M;
    // Eigen matrices are column-major: write row by row for a layout independent of that.
    for (std::size_t k = 0; k < K; ++k)
        for (int d = 0; d < m.dim; ++d) put<float>(out, m.mean(Eigen::Index(k), d));
    for (std::size_t k = 0; k < K; ++k)
        for (int d = 0; d < m.dim; ++d) put<float>(out, m.var(Eigen::Index(k), d));
    put_floats(out, m.weight.data(), K);
    put_floats(out, m.log_self.data(), m.T);
    put_floats(out, m.log_next.data(), m.T);
    put_floats(out, m.super_log_self.data(), m.S);
    put_floats(out, m.super_log_next.data(), m.S);
    for (int s = 0; s < m.S; ++s) put<int32_t>(out, m.band_first[s]), put<int32_t>(out, m.band_last[s]);
}

EmbeddedHmm EmbeddedHmm::read(std::istream& in, uint32_t format_version) {
    const EhmmParams p = read_ehmm_params(in, format_version);
    auto impl = std::make_shared<Impl>();
    Impl& m = *impl;
    m.set_topology(p);
    const std::size_t K = std::size_t(m.T) * m.M;
    for (std::size_t k = 0; k < K; ++k)
        for (int d = 0; d < m.dim; ++d) m.mean(Eigen::Index(k), d) = get<float>(in);
    for (std::size_t k = 0; k < K; ++k)
        for (int d = 0; d < m.dim; ++d) {
            const float v = get<float>(in);
            if (!(v > 0) || !std::isfinite(v)) throw ModelFormatError("<stream>", "embedded HMM with a non-positive variance");
            m.var(Eigen::Index(k), d) = v;
        }
    get_floats(in, m.weight.data(), K);
    get_floats(in, m.log_self.data(), m.T);
    get_floats(in, m.log_next.data(), m.T);
    get_floats(in, m.super_log_self.data(), m.S);
    get_floats(in, m.super_log_next.data(), m.S);
    if (format_version >= 3) {
        const int R = p.observations.grid().height;
        for (int s = 0; s < m.S; ++s) {
            m.band_first[s] = get<int32_t>(in);
            m.band_last[s] = get<int32_t>(in);
        }
        // Every row must be reachable by some super-state, in order: bands start in row 0,
        // end in the last row, and each starts no later than one past the previous one's end.
        bool ok = m.band_first[0] == 0 && m.band_last[m.S - 1] == R - 1;
        for (int s = 0; s < m.S && ok; ++s) {
            ok = m.band_first[s] >= 0 && m.band_first[s] <= m.band_last[s] && m.band_last[s] < R;
            if (s > 0) ok = ok && m.band_first[s] <= m.band_last[s - 1] + 1 && m.band_last[s] >= m.band_last[s - 1];
        }
        if (!ok) throw ModelFormatError("<stream>", "embedded HMM with inconsistent row bands");
    }
    if (!m.mean.allFinite() || !m.weight.allFinite())
        throw ModelFormatError("<stream>", "embedded HMM with non-finite parameters");
    m.build_emission_weights();
    EmbeddedHmm out;
    out.impl_ = std::move(impl);
    return out;
}

}  // namespace facesocial
