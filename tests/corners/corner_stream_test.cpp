// corner_stream_test.cpp: the co-processor's corner sources (cosim/corners): the table, and the
// stream fed frame by frame with the threshold carried, against each source's direct path: the
// spec model over the whole stream in one run, and the cycle model fed the host driver's
// events in one loop with every read's corners kept by frame; a failed gate's error type.
#include <catch2/catch.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cosim/corners/corners.hpp"
#include "model/image/image.hpp"

using namespace hc;

namespace {

constexpr int kW = 64, kH = 32, kFrames = 3;

std::vector<Image> frames_of(Pattern p) {
    std::vector<Image> fs;
    for (int k = 0; k < kFrames; ++k) fs.push_back(make_pattern(p, kW, kH, k, 7));
    return fs;
}

/// Every frame's mask from the stream of source `s` over `fs`, in the order handed on.
std::vector<std::vector<std::uint8_t>> streamed(corners::Source s, const std::vector<Image>& fs) {
    corners::StreamRequest r;
    r.geometry = Geometry{kW, kH};
    r.frames = static_cast<int>(fs.size());
    r.frame_at = [&fs](int k) { return std::make_shared<const Image>(fs.at(static_cast<std::size_t>(k))); };
    const std::unique_ptr<corners::CornerStream> stream = corners::open_stream(s, std::move(r));
    std::vector<std::vector<std::uint8_t>> out;
    corners::StreamFrame f;
    while (stream->next(f)) {
        CHECK(f.frame == static_cast<int>(out.size()));
        out.push_back(f.mask);
    }
    return out;
}

/// The spec model's path: one run over the whole stream, the maximum carried within it.
std::vector<std::vector<std::uint8_t>> spec_in_one_run(const std::vector<Image>& fs) {
    std::vector<const Image*> ptrs;
    for (const auto& f : fs) ptrs.push_back(&f);
    std::vector<std::vector<std::uint8_t>> out;
    for (auto& fc : spec::SpecStream().run(ptrs, 1)) out.push_back(std::move(fc.mask));
    return out;
}

/// The cycle model's path: HostDriver's events into HarrisTop in one BusLoop, each read's
/// corners set in its frame's mask.
std::vector<std::vector<std::uint8_t>> cycle_in_one_loop(const std::vector<Image>& fs) {
    std::vector<const Image*> ptrs;
    for (const auto& f : fs) ptrs.push_back(&f);
    const Geometry g{kW, kH};
    HostDriver drv(g, ptrs);
    HarrisTop top(g, Formats{});
    struct Hooks : BusHooks {
        std::vector<std::vector<std::uint8_t>> masks;
        void read(const BusEvent&, std::uint32_t, const std::vector<Corner>& cs) {
            for (const Corner& c : cs) masks.at(static_cast<std::size_t>(c.frame))[static_cast<std::size_t>(c.y * kW + c.x)] = 1;
        }
    } h;
    h.masks.assign(fs.size(), std::vector<std::uint8_t>(static_cast<std::size_t>(kW * kH), 0));
    BusLoop loop(drv, top);
    loop.run(h);
    return h.masks;
}

long corners_in(const std::vector<std::vector<std::uint8_t>>& masks) {
    long n = 0;
    for (const auto& m : masks) n += spec::count_corners(m);
    return n;
}

}  // namespace

TEST_CASE("the co-processor's corner sources are one table", "[corners]") {
    const auto& t = corners::source_table();
    std::string names;
    for (std::size_t i = 0; i < t.size(); ++i) {
        CHECK(static_cast<std::size_t>(t[i].id) == i);   // in the enum's order
        CHECK(corners::parse_source(t[i].name) == t[i].id);
        CHECK(corners::source_name(t[i].id) == t[i].name);
        CHECK(*t[i].help);
        names += (i ? ", " : "") + std::string(t[i].name);
    }
    CHECK(corners::source_list() == names);
    CHECK_THAT(corners::source_list(), Catch::StartsWith("spec, cycle, rtl"));
    CHECK_FALSE(corners::source_info(corners::Source::spec).cycle_accurate);
    CHECK(corners::source_info(corners::Source::cycle).cycle_accurate);
    CHECK(corners::source_info(corners::Source::cycle).observed);
    CHECK_FALSE(corners::source_info(corners::Source::cycle).needs_simulator);
    CHECK(corners::source_info(corners::Source::rtl).needs_simulator);
    CHECK_FALSE(corners::source_info(corners::Source::rtl).observed);
    CHECK_THROWS_WITH(corners::parse_source("fpga"), Catch::Contains("unknown corner source 'fpga'") && Catch::Contains(names));
    CHECK_THROWS_WITH(corners::parse_source("fpga", "--source"), Catch::Contains("unknown --source 'fpga'"));
}

TEST_CASE("the spec and cycle streams, frame by frame, give the corners of each source's own path", "[corners]") {
    using Path = std::vector<std::vector<std::uint8_t>> (*)(const std::vector<Image>&);
    const std::vector<std::pair<corners::Source, Path>> sources{{corners::Source::spec, spec_in_one_run},
                                                                {corners::Source::cycle, cycle_in_one_loop}};
    for (const auto& [source, path] : sources)
        for (const Pattern p : {Pattern::blocks, Pattern::random}) {
            INFO(corners::source_name(source) << " on " << pattern_name(p));
            const std::vector<Image> fs = frames_of(p);
            const auto want = path(fs);
            CHECK(corners_in(want) > 0);
            CHECK(streamed(source, fs) == want);
        }
}

TEST_CASE("a stream refuses formats the co-processor cannot have", "[corners]") {
    corners::StreamRequest r;
    r.geometry = Geometry{kW, kH};
    r.frames = 1;
    r.frame_at = [](int) { return std::make_shared<const Image>(kW, kH); };
    r.formats.resp_w = 0;
    CHECK_THROWS_AS(corners::open_stream(corners::Source::spec, std::move(r)), InputError);
}

TEST_CASE("a gate that does not pass stops the rtl source with its verdict's status", "[corners]") {
    vl::GateResult g;
    CHECK_NOTHROW(corners::require_gate_pass(corners::Source::rtl, g));
    g.first = "max (find_max) differs at write 1";
    g.verdict = vl::GateVerdict::translation_fault;
    CHECK_THROWS_AS(corners::require_gate_pass(corners::Source::rtl, g), TranslationFault);
    CHECK_THROWS_WITH(corners::require_gate_pass(corners::Source::rtl, g),
                      Catch::Contains("corner source rtl") && Catch::Contains("translation fault") &&
                          Catch::Contains("max (find_max) differs at write 1"));
    g.verdict = vl::GateVerdict::rtl_fault;
    CHECK_THROWS_AS(corners::require_gate_pass(corners::Source::rtl, g), MismatchError);
}
