#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "model/driver/bus_loop.hpp"
#include "model/driver/model_run.hpp"
#include "model/harris/harris_top.hpp"

using namespace hc;

namespace {

/// A golden reads file without its '#' header lines.
std::string golden_rows(const std::string& name) {
    std::ifstream f(std::string(HC_SOURCE_DIR) + "/golden/" + name);
    REQUIRE(f);
    std::ostringstream out;
    for (std::string line; std::getline(f, line);)
        if (line.empty() || line[0] != '#') out << line << '\n';
    return out.str();
}

std::vector<Image> checkerboard_33x21() {
    std::vector<Image> frames;
    for (int k = 0; k < 3; ++k) frames.push_back(make_pattern(Pattern::checkerboard, 33, 21, k, 1));
    return frames;
}

}  // namespace

TEST_CASE("the cycle model alone reads what the golden file of its stream lists", "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const ModelRun r = run_cycle_model(frames, Formats{}, true);
    CHECK(r.reads_csv == golden_rows("reads_checkerboard_33x21.csv"));
    const Geometry g{33, 21};
    CHECK(r.writes == 3 * g.frame_writes());
    long rows = -1;   // the header
    for (char c : r.reads_csv) rows += c == '\n';
    CHECK(r.reads == rows);
    REQUIRE(r.corners_per_frame.size() == 3);
    CHECK(r.corners() == r.corners_per_frame[0] + r.corners_per_frame[1] + r.corners_per_frame[2]);
}

TEST_CASE("the cycle model alone lists no reads unless asked and counts the same", "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const ModelRun with = run_cycle_model(frames, Formats{}, true);
    const ModelRun without = run_cycle_model(frames, Formats{}, false);
    CHECK(without.reads_csv.empty());
    CHECK(without.writes == with.writes);
    CHECK(without.reads == with.reads);
    CHECK(without.corners_per_frame == with.corners_per_frame);
}

namespace {

/// A loop's record: every write's event and every read's value, with hooks that stop the loop
/// at a write count (more) or before a frame's body (before).
struct Record : BusHooks {
    const HarrisTop& top;
    long stop_at = 0;         ///< 0: no write count
    int stop_before = -1;     ///< -1: no frame
    std::vector<std::uint32_t> data, values;
    long corners = 0;
    bool more() const { return stop_at == 0 || top.writes() < stop_at; }
    bool before(const BusEvent& ev) const { return ev.pos.tail || ev.pos.frame != stop_before; }
    void read(const BusEvent&, std::uint32_t v, const std::vector<Corner>& cs) {
        values.push_back(v);
        corners += static_cast<long>(cs.size());
    }
    void after(const BusEvent& ev) { data.push_back(ev.data); }
};

}  // namespace

TEST_CASE("the host-driver loop reads and decodes what the cycle model alone reads", "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const ModelRun alone = run_cycle_model(frames, Formats{}, false);
    const Geometry g{33, 21};
    HostDriver drv(g, {&frames[0], &frames[1], &frames[2]});
    HarrisTop top(g, Formats{});
    Record rec{{}, top};
    BusLoop loop(drv, top);
    CHECK_FALSE(loop.run(rec));   // the stream's end
    CHECK(static_cast<long>(rec.data.size()) == alone.writes);
    CHECK(static_cast<long>(rec.values.size()) == alone.reads);
    CHECK(rec.corners == alone.corners());
}

TEST_CASE("the host-driver loop stops at a write count or before a frame's body and resumes where it stopped",
          "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const Geometry g{33, 21};
    const std::vector<const Image*> ptrs{&frames[0], &frames[1], &frames[2]};
    HostDriver whole_drv(g, ptrs);
    HarrisTop whole_top(g, Formats{});
    Record whole{{}, whole_top};
    BusLoop whole_loop(whole_drv, whole_top);
    whole_loop.run(whole);
    long body1 = 0;   // writes before frame 1's body: frame 0 and frame 1's preloaded columns
    HostDriver count(g, ptrs);
    for (BusEvent ev; count.next(ev) && (ev.pos.tail || ev.pos.frame != 1);) ++body1;

    HostDriver drv(g, ptrs);
    HarrisTop top(g, Formats{});
    Record part{{}, top};
    BusLoop loop(drv, top);
    part.stop_at = 100;
    CHECK(loop.run(part));
    CHECK(top.writes() == 100);
    part.stop_at = 0;
    part.stop_before = 1;
    CHECK(loop.run(part));
    const long at_body = top.writes();
    CHECK(at_body == body1);
    CHECK(loop.run(part));                        // the held event is refused again: no write
    CHECK(top.writes() == at_body);
    part.stop_before = -1;
    CHECK_FALSE(loop.run(part));
    CHECK(part.data == whole.data);
    CHECK(part.values == whole.values);
}
