// The cycle model's instances compiled for fixed formats compute every register exactly as
// the instance that reads the formats at run time, write by write.
#include <catch2/catch.hpp>

#include "model/driver/host_driver.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/harris_top.hpp"

using namespace hc;

TEST_CASE("every compiled instance holds the run-time instance's registers after every write of a 3-frame stream",
          "[model][harris_top]") {
    const Geometry g{64, 24};
    const Image a = make_pattern(Pattern::blocks, g.width, g.height, 0),
                b = make_pattern(Pattern::blocks, g.width, g.height, 1),
                c = make_pattern(Pattern::random, g.width, g.height, 2);
    const std::vector<Formats> all = compiled_formats();
    REQUIRE(all.front() == Formats{});
    for (const Formats& f : all) {
        INFO("formats " << formats_to_json(f));
        HostDriver drv(g, {&a, &b, &c});
        HarrisTop compiled(g, f), run_time(g, f, Specialisation::run_time);
        REQUIRE(compiled.compiled());
        REQUIRE_FALSE(run_time.compiled());
        BusEvent ev;
        long corner_bits = 0, mismatched_writes = 0, first_mismatch = 0;
        while (drv.next(ev)) {
            compiled.write(ev.data);
            run_time.write(ev.data);
            const FlatObservation x = flatten(compiled.observe(), f), y = flatten(run_time.observe(), f);
            if (x.bits != y.bits || x.defined != y.defined || compiled.find_max().count != run_time.find_max().count) {
                if (mismatched_writes++ == 0) first_mismatch = compiled.writes();
            }
            if (ev.read) corner_bits += __builtin_popcount(compiled.corner());
        }
        INFO("first mismatching write " << first_mismatch);
        CHECK(mismatched_writes == 0);
        CHECK(compiled.writes() == drv.total_writes());
        CHECK(corner_bits > 0);   // the stream reaches the corner bits
    }
}

TEST_CASE("formats with no compiled instance run on the run-time instance", "[model][harris_top]") {
    Formats f;
    f.sobel_w = 12;
    REQUIRE_FALSE(has_compiled_instance(f));
    const HarrisTop top(Geometry{64, 24}, f);
    CHECK_FALSE(top.compiled());
    CHECK(HarrisTop(Geometry{64, 24}, Formats{}).compiled());
}
