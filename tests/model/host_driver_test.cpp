#include <catch2/catch.hpp>

#include <map>

#include "model/driver/host_driver.hpp"

using namespace hc;

TEST_CASE("the host driver writes (rows/2-3)*(cols/2+3)*7 words per frame and reads cols/2-3 per window row",
          "[model][host_driver]") {
    for (auto [w, h] : std::vector<std::pair<int, int>>{{20, 16}, {21, 17}, {64, 36}}) {
        const Geometry g{w, h};
        const Image a = make_pattern(Pattern::random, w, h, 0), b = make_pattern(Pattern::random, w, h, 1),
                    c = make_pattern(Pattern::random, w, h, 2);
        HostDriver drv(g, {&a, &b, &c});
        long writes = 0, reads = 0;
        std::map<int, long> reads_per_frame;
        BusEvent ev;
        while (drv.next(ev)) {
            ++writes;
            if (ev.read) {
                ++reads;
                ++reads_per_frame[ev.read->frame];
            }
        }
        INFO("size " << w << "x" << h);
        CHECK(writes == 3L * (h / 2 - 3) * (w / 2 + 3) * 7);
        CHECK(writes == drv.total_writes());
        CHECK(reads == drv.total_reads());
        // every window of frames 0 and 1 is read once; the last frame misses its last two
        CHECK(reads_per_frame[0] == static_cast<long>(h / 2 - 3) * (w / 2 - 3));
        CHECK(reads_per_frame[2] == static_cast<long>(h / 2 - 3) * (w / 2 - 3) - 2);
    }
}

TEST_CASE("each word packs quadrant q's pixel in byte q", "[model][host_driver]") {
    const Geometry g{20, 16};
    Image im(20, 16);
    for (int r = 0; r < 16; ++r)
        for (int c = 0; c < 20; ++c) im.at(r, c) = static_cast<std::uint8_t>(r * 16 + c);
    HostDriver drv(g, {&im});
    BusEvent ev;
    REQUIRE(drv.next(ev));   // i = 3, j = 0, k = -3: row 0, column 0
    const int di = 16 / 2 - 3, dj = 20 / 2 - 3;
    CHECK((ev.data & 0xFF) == im.at(0, 0));
    CHECK(((ev.data >> 8) & 0xFF) == im.at(0 + di, 0));
    CHECK(((ev.data >> 16) & 0xFF) == im.at(0, dj));
    CHECK(((ev.data >> 24) & 0xFF) == im.at(di, dj));
}

TEST_CASE("read bits map to the four quadrant centres, bit 3 first", "[model][host_driver]") {
    const Geometry g{40, 30};
    const Image im(40, 30);
    HostDriver drv(g, {&im});
    std::vector<Corner> out;
    drv.decode(ReadPos{0, 5, 7}, 0xF, out);
    const int di = 30 / 2 - 3, dj = 40 / 2 - 3;
    REQUIRE(out.size() == 4);
    CHECK(out[0] == Corner{0, 5, 7});
    CHECK(out[1] == Corner{0, 5, 7 + di});
    CHECK(out[2] == Corner{0, 5 + dj, 7});
    CHECK(out[3] == Corner{0, 5 + dj, 7 + di});
}

TEST_CASE("a frame of the wrong size is refused with its index and sizes", "[model][host_driver]") {
    const Image a(20, 16), b(22, 16);
    CHECK_THROWS_WITH(HostDriver(Geometry{20, 16}, {&a, &b}),
                      Catch::Contains("frame 1 is 22x16") && Catch::Contains("20x16"));
}

TEST_CASE("the feed driver sends the host driver's stream, asking for each frame once and holding two", "[model]") {
    const Geometry g{64, 36};
    std::vector<Image> frames;
    std::vector<const Image*> ptrs;
    for (int k = 0; k < 5; ++k) frames.push_back(make_pattern(Pattern::blocks, 64, 36, k));
    for (const Image& f : frames) ptrs.push_back(&f);
    HostDriver host(g, ptrs);
    std::vector<int> asked;
    int live = 0, most_live = 0;
    FeedDriver feed(g, 5, [&](int k) {
        asked.push_back(k);
        most_live = std::max(most_live, ++live);
        return std::shared_ptr<const Image>(&frames[static_cast<std::size_t>(k)], [&](const Image*) { --live; });
    });
    BusEvent a, b;
    long events = 0, same = 0;
    while (host.next(a)) {
        REQUIRE(feed.next(b));
        ++events;
        same += a.data == b.data && a.pos.frame == b.pos.frame && a.pos.j == b.pos.j && a.pos.tail == b.pos.tail &&
                a.read.has_value() == b.read.has_value();
    }
    CHECK_FALSE(feed.next(b));
    CHECK(events == host.total_writes());
    CHECK(same == events);
    CHECK(asked == std::vector<int>{0, 1, 2, 3, 4});
    CHECK(most_live == 2);
}
