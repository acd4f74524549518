// Private representation of an embedded HMM, shared by ehmm.cpp and the classifier bank.
#pragma once

#include <iosfwd>
#include <vector>

#include <Eigen/Core>

#include "facesocial/ehmm.hpp"

namespace facesocial {

using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct EmbeddedHmm::Impl {
    EhmmParams params;
    int dim = 0;  // observation vector length
    int S = 0;    // super-states
    int T = 0;    // embedded states in all
    int M = 0;    // mixtures per state
    std::vector<int> first;  // first embedded state of each super-state, S + 1 entries

    Eigen::MatrixXf mean;    // T*M x dim
    Eigen::MatrixXf var;     // T*M x dim
    Eigen::VectorXf weight;  // T*M, sums to 1 within each state
    std::vector<float> log_self, log_next;              // per embedded state
    std::vector<float> super_log_self, super_log_next;  // per super-state
    /// log_enter[t] = log_next[t - 1] within a super-state, -inf for its first state (derived).
    std::vector<float> log_enter;
    std::vector<int> super_of;  // super-state of each embedded state (derived)
    /// Block rows each super-state may take when scoring (all rows unless learned in training).
    std::vector<int> band_first, band_last;

    // Emission log-density of every Gaussian as one linear map of [x^2, x, 1]:
    // log(w N(x; mu, var)) = sum_j (-x_j^2 / (2 var_j) + x_j mu_j / var_j) + c.
    Eigen::MatrixXf W;  // (2*dim + 1) x T*M: per super-state s a slab of n_s*M columns, m*n_s + i

    void set_topology(const EhmmParams& p);
    /// Derives W and log_enter from the parameters; call after changing any of them.
    void build_emission_weights();

    /// [x^2, x, 1] rows of the observations.
    static void features(const Observations& obs, RowMatrixF& F);
    /// E(n, t) = max over mixtures of the Gaussian log-densities; `best_mixture` (optional)
    /// receives the arg max. With `banded`, a super-state's states get -inf outside its band
    /// of block rows (and their densities are not computed there).
    void emissions(const RowMatrixF& F, RowMatrixF& E, std::vector<int>* best_mixture = nullptr,
                   bool banded = false) const;
    /// The scaled log-probability (Viterbi log-likelihood per observation) of a face whose
    /// [x^2, x, 1] features are F; uses per-thread scratch for the emissions.
    double score_features(const RowMatrixF& F, cv::Size grid) const;
    /// Doubly embedded Viterbi; fills `seg` when not null.
    double viterbi(const RowMatrixF& E, cv::Size grid, EhmmSegmentation* seg) const;
};

/// The parameters as stored at the head of a model (and in bank files).
void write_ehmm_params(std::ostream& out, const EhmmParams& p);
/// Reads and validates them as written in `layout` (EmbeddedHmm::kLayoutVersion or older);
/// ModelFormatError("<stream>", ...) when short or invalid.
EhmmParams read_ehmm_params(std::istream& in, uint32_t layout);

}  // namespace facesocial
