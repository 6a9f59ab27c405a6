// association.cpp: individual gating with nearest neighbour, and joint compatibility branch
// and bound over the gated candidates (the joint innovation's covariance grown by one
// pairing at a time through its Cholesky factor).
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <unordered_map>

#include <Eigen/Cholesky>

#include "mapping/slam/association.hpp"
#include "mapping/slam/consistency.hpp"

namespace hc::slam {

namespace {

/// One candidate pairing: observation i with landmark `id`, in the coordinates of the
/// sub-state (robot + the candidates' landmarks).
struct Pairing {
    int obs = 0, id = 0, sub = 0;   ///< sub: column of the landmark's x in the sub-state
    int g = 0;                      ///< index among all pairings of the frame
    Vec2 z;                         ///< innovation
    Mat23 Hr;
    Mat2 Hl;
    double d2 = 0;                  ///< individual Mahalanobis distance
    Mat23 HPr;                      ///< H · P_sub's robot columns
    Mat2 R;                         ///< the observation's noise covariance in this pairing
};

/// Columns c..c+C-1 of a pairing's H · P_sub = Hr P_sub[0:3, :] + Hl P_sub[sub:sub+2, :].
template <int C>
Eigen::Matrix<double, 2, C> HP_cols(const Eigen::MatrixXd& P, const Pairing& p, int c) {
    return p.Hr * P.block<3, C>(0, c) + p.Hl * P.block<2, C>(p.sub, c);
}

/// The sub-state (robot, then each candidate landmark once), its covariance, and every
/// pairing of observation i with its candidates, sorted by increasing individual distance.
struct Gated {
    std::vector<int> idx;   ///< state indices of the sub-state
    Eigen::MatrixXd P;      ///< covariance of the sub-state
    std::vector<std::vector<Pairing>> pairings;
    int count = 0;          ///< pairings over all observations
};

/// The noise of observation i paired with its c-th candidate.
const Mat2& pairing_noise(const std::vector<RangeBearing>& obs, const PairingNoise& noise, int i, size_t c) {
    return noise.empty() ? obs[i].R : noise.at(i).at(c);
}

Gated gate(const Ekf& ekf, const std::vector<RangeBearing>& obs, const std::vector<std::vector<int>>& candidates,
           const PairingNoise& noise) {
    const int N = static_cast<int>(obs.size());
    Gated gd;
    gd.idx = {0, 1, 2};
    std::unordered_map<int, int> sub_of;
    for (int i = 0; i < N; ++i)
        for (int id : candidates.at(i))
            if (!sub_of.count(id)) {
                sub_of[id] = static_cast<int>(gd.idx.size());
                const int l = ekf.state_index(id);
                gd.idx.push_back(l);
                gd.idx.push_back(l + 1);
            }
    gd.P = ekf.covariance_of(gd.idx);
    const Eigen::MatrixXd& P = gd.P;
    const Eigen::VectorXd x = ekf.mean();
    const Pose r = x.head<3>();
    gd.pairings.resize(N);
    for (int i = 0; i < N; ++i) {
        for (size_t c = 0; c < candidates[i].size(); ++c) {
            const int id = candidates[i][c];
            Pairing p;
            p.obs = i;
            p.id = id;
            p.R = pairing_noise(obs, noise, i, c);
            p.sub = sub_of[id];
            const Vec2 yh = observe(r, x.segment<2>(ekf.state_index(id)), &p.Hr, &p.Hl);
            p.z = obs[i].y - yh;
            p.z(1) = wrap_angle(p.z(1));
            p.HPr = HP_cols<3>(P, p, 0);
            const Mat2 S = p.HPr * p.Hr.transpose() + HP_cols<2>(P, p, p.sub) * p.Hl.transpose() + p.R;
            p.d2 = p.z.dot(S.ldlt().solve(p.z));
            gd.pairings[i].push_back(std::move(p));
        }
        std::stable_sort(gd.pairings[i].begin(), gd.pairings[i].end(),
                         [](const Pairing& a, const Pairing& b) { return a.d2 < b.d2; });
    }
    for (auto& ps : gd.pairings)
        for (Pairing& p : ps) p.g = gd.count++;
    return gd;
}

/// A candidate pairing's new diagonal block of the joint factor, l = chol(S22), and l⁻¹ r2.
struct Step {
    double l00 = 0, l10 = 0, l11 = 0, w0 = 0, w1 = 0, d2 = 0;   ///< d2: the joint distance with it
};

/// The branch and bound over the gated pairings, the joint innovation's covariance grown by
/// one pairing at a time through its Cholesky factor L (and w = L⁻¹ z).
class JointSearch {
public:
    JointSearch(const std::vector<RangeBearing>& obs, Gated gated, double joint_probability, long max_nodes)
        : N_(static_cast<int>(obs.size())), W_(2 * N_), gd_(std::move(gated)), max_nodes_(max_nodes),
          rem_(N_ + 1, 0), chi2_(N_ + 1, 0), L_(RowMajor::Zero(W_, W_)), w_(Eigen::VectorXd::Zero(W_)),
          Xc_(new double[static_cast<size_t>(gd_.count) * 2 * W_]),
          sums_(new std::array<double, 5>[static_cast<size_t>(gd_.count) * (N_ + 1)]),
          block_stamp_(static_cast<size_t>(gd_.count) * N_, 0), stamp_(N_, 0), used_sub_(gd_.idx.size(), 0) {
        for (int i = N_ - 1; i >= 0; --i) rem_[i] = rem_[i + 1] + (gd_.pairings[i].empty() ? 0 : 1);
        for (int k = 1; k <= N_; ++k) chi2_[k] = chi2_quantile(joint_probability, 2.0 * k);
        best_.landmark.assign(N_, -1);
    }

    Association run() {
        search(0, 0);
        best_.pairings = std::max(best_k_, 0);
        best_.joint_mahalanobis2 = best_d2_;
        best_.nodes = std::min(nodes_, max_nodes_);
        best_.complete = !stopped_;
        return best_;
    }

private:
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

    Mat2 S_between(const Pairing& a, const Pairing& b) const {
        return a.HPr * b.Hr.transpose() + HP_cols<2>(gd_.P, a, b.sub) * b.Hl.transpose();
    }

    void search(int i, double d2) {
        if (stopped_) return;
        if (++nodes_ > max_nodes_) {
            stopped_ = true;
            return;
        }
        const int k = static_cast<int>(chosen_.size());
        if (i == N_) {
            keep_if_better(d2);
            return;
        }
        if (k + rem_[i] > best_k_) {
            for (const Pairing& p : gd_.pairings[i]) {
                if (used_sub_[p.sub]) continue;
                Step s;
                if (!joint_step(p, k, d2, s)) continue;
                push(p, k, s);
                search(i + 1, s.d2);
                used_sub_[p.sub] = 0;
                chosen_.pop_back();
                if (stopped_) return;
            }
        }
        if (k + rem_[i + 1] > best_k_) search(i + 1, d2);   // observation i left unpaired
    }

    void keep_if_better(double d2) {
        const int k = static_cast<int>(chosen_.size());
        if (k > best_k_ || (k == best_k_ && d2 < best_d2_)) {
            best_k_ = k;
            best_d2_ = d2;
            best_.landmark.assign(N_, -1);
            for (const Pairing* p : chosen_) best_.landmark[p->obs] = p->id;
        }
    }

    /// Pairing p's row X = B L⁻ᵀ of the joint factor against the k chosen pairings (B its
    /// block row of the joint S), by forward substitution, and the running sums of X Xᵀ and
    /// X w after each block. Block q depends only on the pairings chosen at depths 0..q, so
    /// it is kept while they stay: stamp_[q] names the pairing pushed at depth q,
    /// block_stamp_[g][q] the one block q of g was computed under. Returns the sums after
    /// block k−1 (x00 x01 x11 xw0 xw1).
    const std::array<double, 5>& joint_row(const Pairing& p, int k) {
        long* bs = &block_stamp_[static_cast<size_t>(p.g) * N_];
        int q0 = k;
        while (q0 > 0 && bs[q0 - 1] != stamp_[q0 - 1]) --q0;
        double* X0 = &Xc_[static_cast<size_t>(2 * p.g) * W_];
        double* X1 = X0 + W_;
        std::array<double, 5>* sm = &sums_[static_cast<size_t>(p.g) * (N_ + 1)];
        for (int q = q0; q < k; ++q) {
            const Mat2 Bq = S_between(p, *chosen_[q]);
            double x00 = 0, x01 = 0, x11 = 0, xw0 = 0, xw1 = 0;
            if (q > 0) x00 = sm[q][0], x01 = sm[q][1], x11 = sm[q][2], xw0 = sm[q][3], xw1 = sm[q][4];
            for (int c = 0; c < 2; ++c) {
                const int j = 2 * q + c;
                const double* Lj = &L_(j, 0);
                double s0 = Bq(0, c), s1 = Bq(1, c);
                for (int m = 0; m < j; ++m) {
                    s0 -= Lj[m] * X0[m];
                    s1 -= Lj[m] * X1[m];
                }
                const double a = s0 / Lj[j], b = s1 / Lj[j];
                X0[j] = a;
                X1[j] = b;
                x00 += a * a;
                x01 += a * b;
                x11 += b * b;
                xw0 += a * w_(j);
                xw1 += b * w_(j);
            }
            sm[q + 1] = {x00, x01, x11, xw0, xw1};
            bs[q] = stamp_[q];
        }
        return sm[k];
    }

    /// Pairing p after the k chosen ones, at joint distance d2: its Schur complement
    /// S22 = l lᵀ (Cholesky of the 2×2, from its lower triangle) and l⁻¹ r2 into `s`. False
    /// when S22 is not positive definite or the joint distance fails the joint gate.
    bool joint_step(const Pairing& p, int k, double d2, Step& s) {
        const std::array<double, 5>& sm = joint_row(p, k);
        Mat2 S22 = S_between(p, p) + p.R;
        Vec2 r2 = p.z;
        if (k > 0) {
            S22(0, 0) -= sm[0];
            S22(0, 1) -= sm[1];
            S22(1, 0) -= sm[1];
            S22(1, 1) -= sm[2];
            r2(0) -= sm[3];
            r2(1) -= sm[4];
        }
        if (S22(0, 0) <= 0) return false;
        s.l00 = std::sqrt(S22(0, 0));
        s.l10 = S22(1, 0) / s.l00;
        const double e11 = S22(1, 1) - s.l10 * s.l10;
        if (e11 <= 0) return false;
        s.l11 = std::sqrt(e11);
        s.w0 = r2(0) / s.l00;
        s.w1 = (r2(1) - s.l10 * s.w0) / s.l11;
        s.d2 = d2 + (s.w0 * s.w0 + s.w1 * s.w1);
        return s.d2 <= chi2_[k + 1];
    }

    /// Pairing p chosen at depth k: its rows of L and w.
    void push(const Pairing& p, int k, const Step& s) {
        const double* X0 = &Xc_[static_cast<size_t>(2 * p.g) * W_];
        const double* X1 = X0 + W_;
        for (int m = 0; m < 2 * k; ++m) {
            L_(2 * k, m) = X0[m];
            L_(2 * k + 1, m) = X1[m];
        }
        L_(2 * k, 2 * k) = s.l00;
        L_(2 * k, 2 * k + 1) = 0;
        L_(2 * k + 1, 2 * k) = s.l10;
        L_(2 * k + 1, 2 * k + 1) = s.l11;
        stamp_[k] = ++next_stamp_;
        w_(2 * k) = s.w0;
        w_(2 * k + 1) = s.w1;
        chosen_.push_back(&p);
        used_sub_[p.sub] = 1;
    }

    const int N_, W_;
    const Gated gd_;
    const long max_nodes_;
    std::vector<int> rem_;       ///< rem_[i]: observations i.. with at least one candidate
    std::vector<double> chi2_;   ///< chi2_[k]: the joint gate for k pairings
    RowMajor L_;                 ///< row-major: the forward substitution reads it by rows
    Eigen::VectorXd w_;          ///< L⁻¹ z
    // written before read, so left uninitialised: X of g, row 0 at [2gW], row 1 at [(2g+1)W];
    // the sums x00 x01 x11 xw0 xw1 of g after blocks 0..q-1 at [g(N+1) + q] (q = 0: zero)
    const std::unique_ptr<double[]> Xc_;
    const std::unique_ptr<std::array<double, 5>[]> sums_;
    std::vector<long> block_stamp_;
    std::vector<long> stamp_;
    long next_stamp_ = 0;
    std::vector<char> used_sub_;   ///< by the landmark's column in the sub-state
    std::vector<const Pairing*> chosen_;
    Association best_;
    int best_k_ = -1;
    double best_d2_ = 0;
    long nodes_ = 0;
    bool stopped_ = false;
};

}  // namespace

Association associate_nearest(const Ekf& ekf, const std::vector<RangeBearing>& obs,
                              const std::vector<std::vector<int>>& candidates, const PairingNoise& noise) {
    struct Pair {
        double d2;
        int obs, id;
    };
    std::vector<Pair> pairs;
    for (int i = 0; i < static_cast<int>(obs.size()); ++i)
        for (size_t c = 0; c < candidates.at(i).size(); ++c) {
            const int id = candidates[i][c];
            pairs.push_back({ekf.innovation(id, obs[i].y, pairing_noise(obs, noise, i, c)).mahalanobis2, i, id});
        }
    std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d2 < b.d2; });
    Association a;
    a.landmark.assign(obs.size(), -1);
    std::unordered_map<int, char> used;
    for (const auto& p : pairs) {
        if (a.landmark[p.obs] >= 0 || used[p.id]) continue;
        a.landmark[p.obs] = p.id;
        used[p.id] = 1;
        ++a.pairings;
    }
    return a;
}

Association associate_jcbb(const Ekf& ekf, const std::vector<RangeBearing>& obs,
                           const std::vector<std::vector<int>>& candidates, double joint_probability,
                           long max_nodes, const PairingNoise& noise) {
    return JointSearch(obs, gate(ekf, obs, candidates, noise), joint_probability, max_nodes).run();
}

}  // namespace hc::slam
