// stage_stimulus.cpp: see stage_stimulus.hpp.
#include "sweep/stage_stimulus.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "golden/golden.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/image/image.hpp"
#include "sweep/smt_word.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

using Pixels3i = std::array<std::array<int, 3>, 3>;

/// The 5x5 window whose centre is `p`, its border repeating the nearest of them.
Window5 around(const Pixels3i& p) {
    Window5 w{};
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) w[y][x] = p[std::clamp(y - 1, 0, 2)][std::clamp(x - 1, 0, 2)];
    return w;
}

/// A 3x3 window whose Sobel gradients at `f` are ix and iy (z3 on the model's stage functions), or nullopt.
std::optional<Pixels3i> window_with_gradients(std::int64_t ix, std::int64_t iy, const Formats& f, std::int64_t rlimit) {
    SmtQuery q;
    q.text = "(set-logic QF_BV)\n";
    std::array<std::array<SmtWord, 3>, 3> px;
    std::vector<std::string> get;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            px[i][j] = {pixel_input(i, j), 8, false};
            q.text += fmt::format("(declare-fun {} () (_ BitVec 8))\n", px[i][j].e);
            get.push_back(px[i][j].e);
        }
    smt_query = &q;
    SmtWord gx, gy;
    try {
        gx = sobel_x<SmtWord>(px, f);
        gy = sobel_y<SmtWord>(px, f);
    } catch (...) {
        smt_query = nullptr;
        throw;
    }
    smt_query = nullptr;
    const auto bits = [](std::int64_t v, int w) { return static_cast<std::uint64_t>(v) & ((std::uint64_t{1} << w) - 1); };
    q.text += fmt::format("(assert (= {} (_ bv{} {})))\n(assert (= {} (_ bv{} {})))\n", gx.e, bits(ix, gx.w), gx.w, gy.e,
                          bits(iy, gy.w), gy.w);
    const Z3Answer a = run_z3(q.text, rlimit, get);
    if (a.sat != Sat::sat) return std::nullopt;
    Pixels3i p{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) p[i][j] = static_cast<int>(a.values.at(pixel_input(i, j)));
    return p;
}

}  // namespace

std::optional<Window5> stimulus_window(const StageProof& p, const Formats& f, std::int64_t rlimit) {
    if (p.verdict != EqVerdict::counterexample) return std::nullopt;
    const auto& cx = p.counterexample;
    switch (p.stage) {
        case EqStage::sobel_x: case EqStage::sobel_y: {
            Pixels3i px{};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) px[i][j] = static_cast<int>(cx.at(pixel_input(i, j)));
            return around(px);
        }
        case EqStage::m_products: {
            const auto px = window_with_gradients(cx.at("ix"), cx.at("iy"), f, rlimit);
            if (!px) return std::nullopt;
            return around(*px);
        }
        default: return std::nullopt;
    }
}

std::optional<StageStimulus> write_stage_stimulus(const StageProof& p, const Formats& f, const fs::path& dir,
                                                  const std::string& stem, std::int64_t rlimit) {
    const std::optional<Window5> w = stimulus_window(p, f, rlimit);
    if (!w) return std::nullopt;
    const Image im = witness_image(*w);
    const std::string name = file_stem(stem);
    StageStimulus s;
    fs::create_directories(dir);
    s.image = dir / (name + ".pgm");
    s.set = dir / "regression-set.txt";
    util::write_file_atomic(s.image, pgm_bytes(im));
    s.line = fmt::format("{}.pgm  {}x{}  2  0", name, im.width, im.height);
    if (!(f == Formats{})) {
        s.formats = dir / (name + ".json");
        util::write_file_atomic(s.formats, formats_to_json(f, name));
        s.line += fmt::format("  breaks={}.json", name);
    }
    util::write_file_atomic(s.set, fmt::format("# the counterexample of {}'s stage proof as a stimulus (docs/stage-equivalence.md)\n{}\n",
                                               kEqStageNames[static_cast<int>(p.stage)], s.line));
    const std::vector<util::RegressionStream> streams = util::read_regression_set(s.set);
    for (const auto& g : golden::golden_files(streams, dir)) {
        // golden_files adds the tiny streams' register dumps, which are not this stream's
        if (g.path.filename().string().rfind("stages_", 0) == 0) continue;
        util::write_file_atomic(g.path, g.text);
        s.golden.push_back(g.path);
    }
    return s;
}

}  // namespace hc::sweep
