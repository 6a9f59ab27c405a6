// harris_top_test.cpp: the cycle model of harris_top over whole chained streams, with the
// exact counts: writes from the geometry, reads and corner bits from the reviewed golden
// files of the regression set (golden/reads_*.csv), and none on a flat image.
#include <catch2/catch.hpp>

#include <sstream>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "model/util/util.hpp"

using namespace hc;

namespace {

struct Counts {
    long writes = 0, reads = 0, corner_bits = 0;
};

Counts run(Pattern p, int w, int h, int frames) {
    std::vector<Image> imgs;
    for (int k = 0; k < frames; ++k) imgs.push_back(make_pattern(p, w, h, k, 1));
    std::vector<const Image*> ptrs;
    for (const auto& i : imgs) ptrs.push_back(&i);
    const Geometry g{w, h};
    HostDriver drv(g, ptrs);
    HarrisTop top(g, Formats{});
    BusEvent ev;
    Counts c;
    while (drv.next(ev)) {
        top.write(ev.data);
        if (ev.read) {
            ++c.reads;
            c.corner_bits += __builtin_popcount(top.corner());
        }
    }
    c.writes = top.writes();
    return c;
}

/// Reads and corner bits of a golden reads file (write,frame,x,y,value rows).
Counts golden(const std::string& stem) {
    std::istringstream in(util::read_file(std::string(HC_SOURCE_DIR) + "/golden/reads_" + stem + ".csv"));
    Counts c;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#' || line[0] == 'w') continue;
        ++c.reads;
        c.corner_bits += __builtin_popcountl(std::stoul(line.substr(line.rfind(',') + 1)));
        c.writes = std::stol(line.substr(0, line.find(',')));
    }
    return c;
}

}  // namespace

TEST_CASE("three chained 40x30 frames take (h/2-3)*(w/2+3)*7 writes each and read what the golden file holds",
          "[model][harris_top]") {
    const Counts c = run(Pattern::blocks, 40, 30, 3);
    CHECK(c.writes == 3 * (30 / 2 - 3) * (40 / 2 + 3) * 7);   // 5796
    CHECK(c.writes == 5796);
    const Counts g = golden("blocks_40x30");
    CHECK(c.reads == g.reads);               // 610
    CHECK(c.reads == 610);
    CHECK(c.corner_bits == g.corner_bits);   // 26
    CHECK(c.corner_bits == 26);
    CHECK(g.writes == 5796);                 // the last read comes with the last write
}

TEST_CASE("an odd-sized 33x21 stream reads the golden file's corners", "[model][harris_top]") {
    const Counts c = run(Pattern::random, 33, 21, 3);
    const Counts g = golden("random_33x21");
    CHECK(c.writes == 3 * (21 / 2 - 3) * (33 / 2 + 3) * 7);
    CHECK(c.reads == g.reads);
    CHECK(c.corner_bits == g.corner_bits);
}

TEST_CASE("a flat image has no corner: every response equals the threshold and none is a strict maximum",
          "[model][harris_top]") {
    const Counts c = run(Pattern::flat, 40, 30, 3);
    CHECK(c.reads == 610);
    CHECK(c.corner_bits == 0);
}
