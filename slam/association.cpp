// association.cpp: individual gating with nearest neighbour, and joint compatibility branch
// and bound over the gated candidates (the joint innovation's covariance grown by one
// pairing at a time through its Cholesky factor).
#include <algorithm>
#include <functional>
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
    Vec2 z;                         ///< innovation
    Mat23 Hr;
    Mat2 Hl;
    double d2 = 0;                  ///< individual Mahalanobis distance
    Eigen::Matrix<double, 2, Eigen::Dynamic> HP;   ///< H · P_sub
};

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
            p.HP = p.Hr * P.topRows<3>() + p.Hl * P.middleRows<2>(p.sub);
            const Mat2 S = p.HP.leftCols<3>() * p.Hr.transpose() + p.HP.middleCols<2>(p.sub) * p.Hl.transpose() + obs[i].R;
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

    Eigen::MatrixXd L = Eigen::MatrixXd::Zero(2 * N, 2 * N);   // Cholesky factor of the joint S
    Eigen::VectorXd w = Eigen::VectorXd::Zero(2 * N);         // L⁻¹ z
    std::vector<const Pairing*> chosen;
    std::unordered_map<int, char> used;
    Association best;
    best.landmark.assign(N, -1);
    int best_k = -1;
    double best_d2 = 0;
    long nodes = 0;
    bool stopped = false;

    const auto S_between = [&](const Pairing& a, const Pairing& b) -> Mat2 {
        return a.HP.leftCols<3>() * b.Hr.transpose() + a.HP.middleCols<2>(b.sub) * b.Hl.transpose();
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
                if (used[p.id]) continue;
                // the new block row of the joint covariance and of its Cholesky factor
                Eigen::Matrix<double, 2, Eigen::Dynamic> B(2, 2 * k);
                for (int q = 0; q < k; ++q) B.middleCols<2>(2 * q) = S_between(p, *chosen[q]);
                Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, 2 * k);
                if (k > 0)
                    X = L.topLeftCorner(2 * k, 2 * k).triangularView<Eigen::Lower>().solve(B.transpose()).transpose();
                Mat2 S22 = S_between(p, p) + obs[i].R;
                if (k > 0) S22 -= X * X.transpose();
                const Eigen::LLT<Mat2> llt(S22);
                if (llt.info() != Eigen::Success) continue;
                Vec2 r2 = p.z;
                if (k > 0) r2 -= X * w.head(2 * k);
                const Vec2 w2 = llt.matrixL().solve(r2);
                const double d2n = d2 + w2.squaredNorm();
                if (!(d2n <= chi2[k + 1])) continue;
                if (k > 0) L.block(2 * k, 0, 2, 2 * k) = X;
                L.block<2, 2>(2 * k, 2 * k) = llt.matrixL();
                w.segment<2>(2 * k) = w2;
                chosen.push_back(&p);
                used[p.id] = 1;
                search(i + 1, d2n);
                used[p.id] = 0;
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
