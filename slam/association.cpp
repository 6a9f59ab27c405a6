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

#include "slam/association.hpp"

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
};

/// Columns c..c+C-1 of a pairing's H · P_sub = Hr P_sub[0:3, :] + Hl P_sub[sub:sub+2, :].
template <int C>
Eigen::Matrix<double, 2, C> HP_cols(const Eigen::MatrixXd& P, const Pairing& p, int c) {
    return p.Hr * P.block<3, C>(0, c) + p.Hl * P.block<2, C>(p.sub, c);
}

}  // namespace

Association associate_nearest(const Ekf& ekf, const std::vector<RangeBearing>& obs,
                              const std::vector<std::vector<int>>& candidates) {
    struct Pair {
        double d2;
        int obs, id;
    };
    std::vector<Pair> pairs;
    for (int i = 0; i < static_cast<int>(obs.size()); ++i)
        for (int id : candidates.at(i)) pairs.push_back({ekf.innovation(id, obs[i].y, obs[i].R).mahalanobis2, i, id});
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
                           long max_nodes) {
    const int N = static_cast<int>(obs.size());
    // the sub-state: robot, then each candidate landmark once
    std::vector<int> idx{0, 1, 2};
    std::unordered_map<int, int> sub_of;
    for (int i = 0; i < N; ++i)
        for (int id : candidates.at(i))
            if (!sub_of.count(id)) {
                sub_of[id] = static_cast<int>(idx.size());
                const int l = ekf.state_index(id);
                idx.push_back(l);
                idx.push_back(l + 1);
            }
    const Eigen::MatrixXd P = ekf.covariance_of(idx);
    const Eigen::VectorXd x = ekf.mean();
    const Pose r = x.head<3>();
    std::vector<std::vector<Pairing>> pairings(N);
    for (int i = 0; i < N; ++i) {
        for (int id : candidates[i]) {
            Pairing p;
            p.obs = i;
            p.id = id;
            p.sub = sub_of[id];
            const Vec2 yh = observe(r, x.segment<2>(ekf.state_index(id)), &p.Hr, &p.Hl);
            p.z = obs[i].y - yh;
            p.z(1) = wrap_angle(p.z(1));
            p.HPr = HP_cols<3>(P, p, 0);
            const Mat2 S = p.HPr * p.Hr.transpose() + HP_cols<2>(P, p, p.sub) * p.Hl.transpose() + obs[i].R;
            p.d2 = p.z.dot(S.ldlt().solve(p.z));
            pairings[i].push_back(std::move(p));
        }
        std::stable_sort(pairings[i].begin(), pairings[i].end(),
                         [](const Pairing& a, const Pairing& b) { return a.d2 < b.d2; });
    }
    // rem[i]: observations i.. with at least one candidate
    std::vector<int> rem(N + 1, 0);
    for (int i = N - 1; i >= 0; --i) rem[i] = rem[i + 1] + (pairings[i].empty() ? 0 : 1);
    std::vector<double> chi2(N + 1, 0);
    for (int k = 1; k <= N; ++k) chi2[k] = chi2_quantile(joint_probability, 2.0 * k);

    // Cholesky factor of the joint S, row-major: the forward substitution reads it by rows
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> L =
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Zero(2 * N, 2 * N);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(2 * N);         // L⁻¹ z
    // Per pairing g, its row X = B L⁻ᵀ of the joint factor against the chosen pairings (B its
    // block row of the joint S), solved by forward substitution, and the running sums of
    // X Xᵀ and X w after each block. Block q depends only on the pairings chosen at depths
    // 0..q, so it is kept while they stay: stamp[q] names the pairing pushed at depth q,
    // block_stamp[g][q] the one block q of g was computed under.
    int G = 0;
    for (auto& ps : pairings)
        for (Pairing& p : ps) p.g = G++;
    const int W = 2 * N;
    // written before read, so left uninitialised: X of g, row 0 at [2gW], row 1 at [(2g+1)W];
    // the sums x00 x01 x11 xw0 xw1 of g after blocks 0..q-1 at [g(N+1) + q] (q = 0: zero)
    const std::unique_ptr<double[]> Xc(new double[static_cast<size_t>(G) * 2 * W]);
    const std::unique_ptr<std::array<double, 5>[]> sums(new std::array<double, 5>[static_cast<size_t>(G) * (N + 1)]);
    std::vector<long> block_stamp(static_cast<size_t>(G) * N, 0);
    std::vector<long> stamp(N, 0);
    long next_stamp = 0;
    std::vector<char> used_sub(idx.size(), 0);   // by the landmark's column in the sub-state
    std::vector<const Pairing*> chosen;
    Association best;
    best.landmark.assign(N, -1);
    int best_k = -1;
    double best_d2 = 0;
    long nodes = 0;
    bool stopped = false;

    const auto S_between = [&](const Pairing& a, const Pairing& b) -> Mat2 {
        return a.HPr * b.Hr.transpose() + HP_cols<2>(P, a, b.sub) * b.Hl.transpose();
    };
    const std::function<void(int, double)> search = [&](int i, double d2) {
        if (stopped) return;
        if (++nodes > max_nodes) {
            stopped = true;
            return;
        }
        const int k = static_cast<int>(chosen.size());
        if (i == N) {
            if (k > best_k || (k == best_k && d2 < best_d2)) {
                best_k = k;
                best_d2 = d2;
                best.landmark.assign(N, -1);
                for (const Pairing* p : chosen) best.landmark[p->obs] = p->id;
            }
            return;
        }
        if (k + rem[i] > best_k) {
            for (const Pairing& p : pairings[i]) {
                if (used_sub[p.sub]) continue;
                // the new block row of the joint covariance and of its Cholesky factor: the
                // blocks still valid for the chosen prefix are reused, the others solved
                long* bs = &block_stamp[static_cast<size_t>(p.g) * N];
                int q0 = k;
                while (q0 > 0 && bs[q0 - 1] != stamp[q0 - 1]) --q0;
                double* X0 = &Xc[static_cast<size_t>(2 * p.g) * W];
                double* X1 = X0 + W;
                std::array<double, 5>* sm = &sums[static_cast<size_t>(p.g) * (N + 1)];
                for (int q = q0; q < k; ++q) {
                    const Mat2 Bq = S_between(p, *chosen[q]);
                    double x00 = 0, x01 = 0, x11 = 0, xw0 = 0, xw1 = 0;
                    if (q > 0) x00 = sm[q][0], x01 = sm[q][1], x11 = sm[q][2], xw0 = sm[q][3], xw1 = sm[q][4];
                    for (int c = 0; c < 2; ++c) {
                        const int j = 2 * q + c;
                        const double* Lj = &L(j, 0);
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
                        xw0 += a * w(j);
                        xw1 += b * w(j);
                    }
                    sm[q + 1] = {x00, x01, x11, xw0, xw1};
                    bs[q] = stamp[q];
                }
                Mat2 S22 = S_between(p, p) + obs[i].R;
                Vec2 r2 = p.z;
                if (k > 0) {
                    S22(0, 0) -= sm[k][0];
                    S22(0, 1) -= sm[k][1];
                    S22(1, 0) -= sm[k][1];
                    S22(1, 1) -= sm[k][2];
                    r2(0) -= sm[k][3];
                    r2(1) -= sm[k][4];
                }
                // S22 = l lᵀ (Cholesky of the 2×2, from its lower triangle) and l⁻¹ r2
                if (S22(0, 0) <= 0) continue;
                const double l00 = std::sqrt(S22(0, 0)), l10 = S22(1, 0) / l00;
                const double e11 = S22(1, 1) - l10 * l10;
                if (e11 <= 0) continue;
                const double l11 = std::sqrt(e11);
                const double w0 = r2(0) / l00, w1 = (r2(1) - l10 * w0) / l11;
                const double d2n = d2 + (w0 * w0 + w1 * w1);
                if (!(d2n <= chi2[k + 1])) continue;
                for (int m = 0; m < 2 * k; ++m) {
                    L(2 * k, m) = X0[m];
                    L(2 * k + 1, m) = X1[m];
                }
                L(2 * k, 2 * k) = l00;
                L(2 * k, 2 * k + 1) = 0;
                L(2 * k + 1, 2 * k) = l10;
                L(2 * k + 1, 2 * k + 1) = l11;
                stamp[k] = ++next_stamp;
                w(2 * k) = w0;
                w(2 * k + 1) = w1;
                chosen.push_back(&p);
                used_sub[p.sub] = 1;
                search(i + 1, d2n);
                used_sub[p.sub] = 0;
                chosen.pop_back();
                if (stopped) return;
            }
        }
        if (k + rem[i + 1] > best_k) search(i + 1, d2);   // observation i left unpaired
    };
    search(0, 0);
    best.pairings = std::max(best_k, 0);
    best.joint_mahalanobis2 = best_d2;
    best.nodes = std::min(nodes, max_nodes);
    best.complete = !stopped;
    return best;
}

}  // namespace hc::slam
