#include <catch2/catch.hpp>

#include "driver/host_driver.hpp"
#include "harris/harris_top.hpp"

using namespace hc;

TEST_CASE("smoke: the cycle model runs a chained stream", "[model][harris_top]") {
    const Geometry g{40, 30};
    const Image a = make_pattern(Pattern::blocks, 40, 30, 0), b = make_pattern(Pattern::blocks, 40, 30, 1);
    HostDriver drv(g, {&a, &b});
    HarrisTop top(g, Formats{});
    BusEvent ev;
    long corners = 0;
    while (drv.next(ev)) {
        top.write(ev.data);
        if (ev.read) corners += __builtin_popcount(top.corner());
    }
    CHECK(top.writes() == drv.total_writes());
    CHECK(corners > 0);
}
