// load_control_test.cpp: unit tests of model/harris/load_control.hpp (rtl/load_control.vhd).
//
// Counts writes in a window row (1..(w/2+3)*7) and rows in a frame (1..h/2-3). The value of
// load after write n of a row: 1 for n = 1..48, 0 for n = 49..R-1, and after the row's last
// write (n = R) 1 again, except after a frame's last row, where it stays 0.
#include <catch2/catch.hpp>

#include <string>

#include "model/harris/load_control.hpp"

using namespace hc;

namespace {
/// load after each write of one frame, as a string of '0'/'1' per row.
std::vector<std::string> frame_load(const Geometry& g, LoadControl& lc) {
    std::vector<std::string> rows;
    for (int r = 0; r < g.rows(); ++r) {
        std::string s;
        for (int n = 0; n < g.row_writes(); ++n) {
            lc = lc.next(g);
            s += lc.load ? '1' : '0';
        }
        rows.push_back(s);
    }
    return rows;
}
}  // namespace

TEST_CASE("load_control starts high and is low after writes 49..R-1 of every row (20x16, R = 91)",
          "[model][load_control]") {
    const Geometry g{20, 16};   // rows = 5, columns = 13, R = 91 writes per row
    REQUIRE(g.row_writes() == 91);
    LoadControl lc;
    CHECK(lc.load);
    const auto rows = frame_load(g, lc);
    const std::string body = std::string(48, '1') + std::string(91 - 48 - 1, '0');
    for (int r = 0; r < g.rows(); ++r) {
        INFO("row " << r + 1 << " of " << g.rows());
        const bool last = r + 1 == g.rows();
        CHECK(rows[r] == body + (last ? "0" : "1"));
    }
}

TEST_CASE("load_control repeats with a period of (h/2-3)*(w/2+3)*7 writes", "[model][load_control]") {
    for (const Geometry g : {Geometry{20, 16}, Geometry{10, 8}, Geometry{41, 31}}) {
        LoadControl lc;
        long n = 0;
        do {
            lc = lc.next(g);
            ++n;
        } while (!(lc.row == 1 && lc.col == 1) && n < 10'000'000);
        INFO("geometry " << g.width << "x" << g.height);
        CHECK(n == g.frame_writes());
        CHECK(n == static_cast<long>(g.height / 2 - 3) * (g.width / 2 + 3) * 7);
    }
}

TEST_CASE("load_control after a frame's last write takes 1 again on the next frame's first write",
          "[model][load_control]") {
    const Geometry g{20, 16};
    LoadControl lc;
    frame_load(g, lc);
    CHECK_FALSE(lc.load);      // low through the frame boundary ...
    lc = lc.next(g);
    CHECK(lc.load);            // ... for exactly one write
    lc.reset();
    CHECK(lc.load);
    CHECK(lc.row == 1);
    CHECK(lc.col == 1);
}
