// sweep_landmarks_test.cpp: the sweep's stereo-match column (correct matches of the landmark
// chain per configuration) equals landmarks::score_formats called directly, and the reports
// carry it. Exits 77 (CTest: skipped) with a message without the Middlebury 2006 half-size
// scenes under the data directory ($HARRIS_COSIM_DATA, else ../shared/data).
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sweep/sweep.hpp"
#include "sweep/sweep_report.hpp"

namespace fs = std::filesystem;
using namespace hc;
using namespace hc::sweep;

namespace {
fs::path g_half;
}

int main(int argc, char** argv) {
    const char* env = std::getenv("HARRIS_COSIM_DATA");
    g_half = (env && *env ? fs::path(env) : fs::path(HC_TEST_DATA_DIR)) / "middlebury2006" / "half";
    if (!fs::exists(g_half / "Aloe" / "disp1.png")) {
        std::printf("SKIP: no Middlebury 2006 half-size scenes under '%s' (set HARRIS_COSIM_DATA)\n", g_half.string().c_str());
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

TEST_CASE("the sweep's stereo-match column is score_formats of each configuration, in every report", "[landmarks][sweep]") {
    LandmarkSpec spec;
    spec.scenes = {"Aloe"};
    const landmarks::Dataset ds = landmark_dataset(g_half, spec);
    REQUIRE(ds.pairs.size() == 1);
    SweepResult r;
    r.spec.landmarks = spec;
    Formats tight;   // the sweep's tight-m3-b2
    tight.m_drop = 3;
    tight.bf_sum_w = 22;
    tight.bf_drop = 2;
    tight.ktr_w = 35;
    tight.resp_w = 38;
    r.points.resize(2);
    r.points[0].config = {"thesis", Formats{}};
    r.points[1].config = {"tight-m3-b2", tight};
    score_landmarks(r.points, ds, spec, 2);
    r.landmark_pairs = describe_landmark_pairs(ds, spec);
    const std::string csv = to_csv(r), md = to_markdown(r);
    const auto js = nlohmann::json::parse(to_json(r));
    for (size_t i = 0; i < r.points.size(); ++i) {
        const PointResult& p = r.points[i];
        INFO(p.config.name);
        const landmarks::Totals direct = landmarks::score_formats(ds, p.config.formats, landmarks::Detector::spec,
                                                                  landmarks::GridParams{16, 3}, landmarks::MatchParams{});
        REQUIRE(p.has_landmarks);
        CHECK(p.landmarks.correct == direct.correct);
        CHECK(p.landmarks.truth_correct == direct.truth_correct);
        CHECK(p.landmarks.all == direct.all);
        CHECK(p.landmarks.keypoints == direct.keypoints);
        CHECK(direct.correct > 1000);   // Aloe: ~2,000 correct matches on the co-processor's corners
        CHECK(csv.find(fmt::format(",{},{},{},{},{},", direct.keypoints, direct.all, direct.correct, direct.truth_known,
                                   direct.truth_correct)) != std::string::npos);
        CHECK(md.find(fmt::format("| {} | {} |", direct.correct, direct.truth_correct)) != std::string::npos);
        CHECK(js["points"][i]["landmarks"]["correct"] == direct.correct);
        CHECK(js["points"][i]["landmarks"]["truth_correct"] == direct.truth_correct);
    }
    // the two configurations differ downstream
    CHECK(r.points[0].landmarks.keypoints != r.points[1].landmarks.keypoints);
    CHECK(md.find("middlebury-half Aloe") != std::string::npos);
}

TEST_CASE("the landmark column's spec: scenes, g and h, or false, a missing scene is an input error", "[landmarks][sweep]") {
    const SweepSpec s = parse_sweep_spec(R"({"configs": [{"name": "a"}], "landmarks": {"scenes": ["Rocks1"], "g": 12, "h": 2}})", "t");
    CHECK(s.landmarks.enabled);
    CHECK(s.landmarks.scenes == std::vector<std::string>{"Rocks1"});
    CHECK(s.landmarks.g == 12);
    CHECK(s.landmarks.h == 2);
    CHECK_FALSE(parse_sweep_spec(R"({"configs": [{"name": "a"}], "landmarks": false})", "t").landmarks.enabled);
    CHECK_THROWS_WITH(parse_sweep_spec(R"({"configs": [{"name": "a"}], "landmarks": {"g": 1}})", "t"),
                      Catch::Contains("landmarks") && Catch::Contains("g"));
    CHECK_THROWS_WITH(parse_sweep_spec(R"({"configs": [{"name": "a"}], "landmarks": {"scene": []}})", "t"),
                      Catch::Contains("unknown key 'scene'"));
    LandmarkSpec missing;
    missing.scenes = {"NoSuchScene"};
    CHECK_THROWS_WITH(landmark_dataset(g_half, missing), Catch::Contains("NoSuchScene"));
}
