// slam_consistency_test.cpp: chi-square quantiles against closed forms, the simulator
// (seeded, field of view, range limit, noise statistics, bad configuration), and the
// filter's Monte-Carlo consistency: the mean NEES over 50 seeds inside the 95 % bounds.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "mapping/slam/slam.hpp"

using namespace hc::slam;

TEST_CASE("chi-square quantiles equal the closed forms of 1, 2 and 4 degrees of freedom", "[slam]") {
    // dof 2: P(x) = 1 - e^(-x/2), so the p-quantile is -2 ln(1 - p)
    for (double p : {0.025, 0.5, 0.95, 0.975, 0.99}) CHECK(chi2_quantile(p, 2) == Approx(-2 * std::log(1 - p)).epsilon(1e-10));
    // dof 1: the square of the normal quantile of (1 + p)/2
    CHECK(normal_quantile(0.975) == Approx(1.959963984540054).epsilon(1e-12));
    CHECK(chi2_quantile(0.95, 1) == Approx(3.841458820694124).epsilon(1e-10));
    // dof 4: P(x) = 1 - e^(-x/2) (1 + x/2)
    for (double p : {0.025, 0.975}) {
        const double x = chi2_quantile(p, 4);
        CHECK(1 - std::exp(-x / 2) * (1 + x / 2) == Approx(p).epsilon(1e-10));
    }
    CHECK(regularized_gamma_p(3.0, 0.0) == 0);
    CHECK(regularized_gamma_p(1.0, 2.0) == Approx(1 - std::exp(-2.0)).epsilon(1e-14));
}

TEST_CASE("Wilson-Hilferty's approximation is within 0.5 % of the exact upper quantile from 3 dof on", "[slam]") {
    for (double dof : {3.0, 6.0, 150.0, 3000.0}) {
        INFO("dof " << dof);
        CHECK(chi2_quantile_wilson_hilferty(0.975, dof) == Approx(chi2_quantile(0.975, dof)).epsilon(5e-3));
    }
    // the lower tail needs many degrees of freedom: 16 % low at 3 dof, within 0.5 % at 150
    CHECK(chi2_quantile_wilson_hilferty(0.025, 3) == Approx(0.1814).epsilon(1e-3));
    CHECK(chi2_quantile(0.025, 3) == Approx(0.2158).epsilon(1e-3));
    CHECK(chi2_quantile_wilson_hilferty(0.025, 150) == Approx(chi2_quantile(0.025, 150)).epsilon(5e-3));
    // the bounds of a 50-run mean of a 3-dof NEES
    CHECK(chi2_quantile(0.025, 150) / 50 == Approx(2.3596).epsilon(2e-3));
    CHECK(chi2_quantile(0.975, 150) / 50 == Approx(3.7160).epsilon(2e-3));
}

TEST_CASE("the simulator is reproducible from its seed and differs between seeds", "[slam]") {
    SimConfig c;
    Simulator a(c, 42), b(c, 42), d(c, 43);
    for (int k = 0; k < 50; ++k) {
        const Vec2 ua = a.step(), ub = b.step(), ud = d.step();
        CHECK(ua == ub);
        CHECK(ua != ud);
        const auto oa = a.observe(), ob = b.observe();
        REQUIRE(oa.size() == ob.size());
        for (size_t i = 0; i < oa.size(); ++i) CHECK(oa[i].y == ob[i].y);
    }
    CHECK(a.true_pose() == d.true_pose());   // the true trajectory does not depend on the seed
}

TEST_CASE("the sensor sees only landmarks within its field of view and range", "[slam]") {
    SimConfig c;
    c.layout = Layout::Random;
    c.landmarks = 300;
    c.half_size = 8;
    c.sensor.fov = std::numbers::pi / 2;
    c.sensor.max_range = 4;
    Simulator s(c, 9);
    int seen = 0;
    for (int k = 0; k < 40; ++k) {
        s.step();
        const auto obs = s.observe();
        std::vector<char> visible(c.landmarks, 0);
        for (const auto& o : obs) visible[o.id] = 1;
        for (int i = 0; i < c.landmarks; ++i) {
            const Vec2 y = observe(s.true_pose(), s.world().landmarks[i]);
            const bool inside = y(0) <= 4 && std::abs(y(1)) <= std::numbers::pi / 4;
            REQUIRE(visible[i] == inside);
        }
        seen += static_cast<int>(obs.size());
    }
    CHECK(seen > 100);
}

TEST_CASE("measurement and odometry noise have the configured standard deviations", "[slam]") {
    SimConfig c;
    c.landmarks = 60;
    c.sensor.sigma_range = 0.2;
    c.sensor.sigma_bearing = 0.05;
    c.odometry.sigma_dx = 0.03;
    c.odometry.sigma_dtheta = 0.01;
    Simulator s(c, 5);
    double sr = 0, sb = 0, sx = 0, st = 0, mr = 0;
    int n = 0, m = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec2 u = s.step();
        sx += std::pow(u(0) - c.step, 2);
        st += std::pow(u(1) - c.step / c.radius, 2);
        ++m;
        for (const auto& o : s.observe_all()) {
            const Vec2 y = observe(s.true_pose(), s.world().landmarks[o.id]);
            sr += std::pow(o.y(0) - y(0), 2);
            mr += o.y(0) - y(0);
            sb += std::pow(wrap_angle(o.y(1) - y(1)), 2);
            ++n;
        }
    }
    CHECK(n == 2000 * 60);
    CHECK(std::sqrt(sr / n) == Approx(0.2).epsilon(0.01));
    CHECK(std::sqrt(sb / n) == Approx(0.05).epsilon(0.01));
    CHECK(std::abs(mr / n) < 0.003);
    CHECK(std::sqrt(sx / m) == Approx(0.03).epsilon(0.05));
    CHECK(std::sqrt(st / m) == Approx(0.01).epsilon(0.05));
}

TEST_CASE("the cloister places its landmarks on two concentric squares", "[slam]") {
    const World w = make_world(Layout::Cloister, 30, 4, 0);
    REQUIRE(w.landmarks.size() == 30);
    int outer = 0, inner = 0;
    for (const auto& p : w.landmarks) {
        const double linf = p.cwiseAbs().maxCoeff();
        outer += std::abs(linf - 4) < 1e-12;
        inner += std::abs(linf - 2) < 1e-12;
    }
    CHECK(outer == 20);
    CHECK(inner == 10);
}

TEST_CASE("bad simulation settings are refused with InputError naming them", "[slam]") {
    SimConfig c;
    c.landmarks = 0;
    CHECK_THROWS_WITH(c.validate(), Catch::Contains("world is empty"));
    c = SimConfig{};
    c.sensor.sigma_range = 0;
    CHECK_THROWS_WITH(c.validate(), Catch::Contains("--sigma-range"));
    c = SimConfig{};
    c.odometry.sigma_dtheta = -1;
    CHECK_THROWS_AS(c.validate(), hc::InputError);
    c = SimConfig{};
    c.sensor.sigma_bearing = std::nan("");
    CHECK_THROWS_WITH(c.validate(), Catch::Contains("--sigma-bearing"));
    CHECK_THROWS_AS(monte_carlo(SimConfig{}, 0, 1), hc::InputError);
}

// The mean over 50 runs is correlated along the run: a 50-seed set can sit just outside
// its bounds for a stretch of steps (measured: 78-100 % of steps inside for five sets of 50
// seeds, 97 % for 400 seeds). The CI test asks the time-averaged mean inside the bounds and
// 75 % of the steps inside; the slow test asks 90 % with 400 seeds.
TEST_CASE("the mean NEES of 50 seeds stays inside the 95 % chi-square bounds", "[slam]") {
    SimConfig c;   // one loop of the cloister, 40 landmarks
    const MonteCarlo mc = monte_carlo(c, 50, 1);
    INFO("pose NEES average " << mc.pose_nees_average << " in [" << mc.pose_lo << ", " << mc.pose_hi << "], "
         << 100 * mc.pose_inside << " % of steps inside; map NEES/dof average " << mc.map_nees_per_dof_average
         << ", " << 100 * mc.map_inside << " % inside");
    CHECK(mc.pose_lo == Approx(chi2_quantile(0.025, 150) / 50));
    CHECK(mc.pose_nees_average > mc.pose_lo);
    CHECK(mc.pose_nees_average < mc.pose_hi);
    CHECK(mc.pose_inside >= 0.75);
    CHECK(mc.map_inside >= 0.75);
    CHECK(mc.map_nees_per_dof_average > mc.map_lo.back());
    CHECK(mc.map_nees_per_dof_average < mc.map_hi.back());
    CHECK(mc.position_rmse.back() < 0.2);
}

TEST_CASE("a filter that assumes half the true noise fails the same NEES test", "[slam]") {
    SimConfig c;
    c.filter_sigma_scale = 0.5;
    const MonteCarlo mc = monte_carlo(c, 50, 1);
    INFO("pose NEES average " << mc.pose_nees_average << ", map NEES/dof average " << mc.map_nees_per_dof_average);
    CHECK(mc.pose_nees_average > 2 * mc.pose_hi);
    CHECK(mc.pose_inside < 0.1);
    CHECK(mc.map_nees_per_dof_average > 2 * mc.map_hi.back());
}

TEST_CASE("the mean NEES of 400 seeds over three loops stays inside the 95 % bounds", "[slam][slow]") {
    SimConfig c;
    c.steps = 3 * 236;
    const MonteCarlo mc = monte_carlo(c, 400, 10000);
    INFO("pose NEES average " << mc.pose_nees_average << " in [" << mc.pose_lo << ", " << mc.pose_hi << "], "
         << 100 * mc.pose_inside << " % of steps inside; map NEES/dof average " << mc.map_nees_per_dof_average
         << ", " << 100 * mc.map_inside << " % inside");
    CHECK(mc.pose_nees_average > mc.pose_lo);
    CHECK(mc.pose_nees_average < mc.pose_hi);
    CHECK(mc.pose_inside >= 0.9);
    CHECK(mc.map_inside >= 0.9);
}
