// fuzz_targets.cpp: see fuzz_targets.hpp.
#include "tests/fuzz/fuzz_targets.hpp"

#include <fstream>
#include <typeinfo>

#include <opencv2/imgcodecs.hpp>

#include "io/cluster/cluster.hpp"
#include "io/frames/frames.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "tests/landmarks/kitti_calib_text.hpp"
#include "model/harris/formats_json.hpp"
#include "mutation/mutation.hpp"
#include "mapping/slam/slam.hpp"
#include "sweep/sweep_config.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::fuzz {

namespace {

std::string file_or_empty(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return in ? std::string(std::istreambuf_iterator<char>(in), {}) : std::string();
}

// A small textured frame, encoded by OpenCV as `ext` (".png", ".jpg").
std::string encoded_frame(const char* ext) {
    cv::Mat m(12, 16, CV_8UC1);
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((x * 37 + y * 11) & 0xff);
    std::vector<std::uint8_t> buf;
    cv::imencode(ext, m, buf);
    return std::string(buf.begin(), buf.end());
}

const std::vector<std::string> kJsonTokens = {
    "{", "}", "[", "]", ":", ",", "\"", "null", "true", "false", "-1", "0", "1", "1e400", "-1e400", "0.5",
    "2147483647", "2147483648", "-2147483649", "18446744073709551616", "\"\"", "\\u0000", "\\ud800", " ", "\n"};
const std::vector<std::string> kTextTokens = {" ", "\t", "\n", "\r\n", "#", "0", "-1", "1e308", "1e400", "nan", "inf",
                                              "-0", "2147483648", "x", ":", "\xff", std::string(1, '\0')};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}  // namespace

std::vector<Target> targets(const fs::path& src) {
    std::vector<Target> t;
    std::vector<std::string> field_tokens;
    for (const auto& f : format_fields()) field_tokens.push_back(std::string("\"") + f.name + "\"");

    // --- frames: PNG/JPEG images (rtl, model, verilate, mutate: --image files) -----------
    t.push_back({"frame-image", "image frames (PNG, JPEG) of rtl/model/verilate", "frame.png",
                 {encoded_frame(".png"), encoded_frame(".jpg"), file_or_empty(src / "tests/data/gray8_8x6.png"),
                  file_or_empty(src / "tests/data/gray16_24x20.png"), file_or_empty(src / "tests/data/corrupt.png")},
                 {"IHDR", "IDAT", "IEND", "\x89PNG\r\n\x1a\n", "\xff\xd8\xff\xe0", "\xff\xd9", "\xff\xc0", "\xff\xda",
                  std::string(4, '\0'), "\xff\xff\xff\xff", "\x7f\xff\xff\xff"},
                 [](const fs::path& p) {
                     frames::FrameSource s;
                     s.images = {p.string()};
                     (void)frames::load_frames(s);
                 }});

    // --- KITTI calib.txt (landmarks --dataset kitti, slam --landmarks-from stereo) --------
    const std::string calib = std::string(landmarks::test::kKitti00P0P1) +
        "P2: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: 1 0 0 0 0 1 0 0 0 0 1 0\n";
    t.push_back({"kitti-calib", "KITTI sequences/NN/calib.txt", "calib.txt", {calib, "P0: 1 2 3\n"},
                 with(kTextTokens, {"P0:", "P1:", "P2:", "Tr:", "e+02", "e-300"}),
                 [](const fs::path& p) {
                     (void)landmarks::read_kitti_calib(p);
                 }});

    // --- KITTI poses/NN.txt (slam --sequence) --------------------------------------------
    t.push_back({"kitti-poses", "KITTI poses/NN.txt", "poses.txt",
                 {"1 0 0 0 0 1 0 0 0 0 1 0\n9.99e-01 5.3e-04 -4.3e-02 -4.6e-02 -5.4e-04 1 -4.6e-04 -2.8e-02 "
                  "4.3e-02 4.7e-04 9.99e-01 8.5e-01\n",
                  "1 0 0 0 0 1 0 0 0 0 1\n"},
                 kTextTokens,
                 [](const fs::path& p) {
                     for (const auto& T : slam::read_kitti_poses(p)) (void)slam::planar_pose(T);
                 }});

    // --- --config formats JSON (rtl, model, verilate, eval, landmarks, slam) ---------------
    t.push_back({"formats-json", "--config formats JSON", "formats.json",
                 {formats_to_json(Formats{}, "thesis"), file_or_empty(src / "tests/data/formats_m_drop_too_large.json"),
                  file_or_empty(src / "tests/data/formats_unknown_key.json"), "{\"m_drop\": 3, \"bf_drop\": 2}"},
                 with(kJsonTokens, field_tokens),
                 [](const fs::path& p) { (void)formats_from_file(p.string()); }});

    // --- sweep specs (sweep --config) ------------------------------------------------------
    t.push_back({"sweep-spec", "sweep --config spec", "spec.json",
                 {file_or_empty(src / "sweep/configs/bit-widths.json"),
                  R"({"name":"s","base":{"m_drop":4},"grid":{"m_drop":[3,4],"bf_drop":[2]},"configs":[{"name":"a"}],)"
                  R"("cost":{"img_width":64,"img_height":36},"trust":{"rtl":false,"verilator_pairs":"0:2",)"
                  R"("verilator_gate":true},"data":{"sequence":"01","pairs":"0:3"}})"},
                 with(with(kJsonTokens, field_tokens),
                      {"\"configs\"", "\"grid\"", "\"base\"", "\"trust\"", "\"cost\"", "\"data\"", "\"pairs\"",
                       "\"sequence\"", "\"verilator_pairs\"", "\"img_width\"", "\"0:5\"", "\"5:\"", "\":\""}),
                 [](const fs::path& p) { (void)sweep::load_sweep_spec(p); }});

    // --- golden/regression-set.txt (sweep's RTL checks) ------------------------------------
    t.push_back({"regression-set", "regression-set lines (golden/regression-set.txt)", "regression-set.txt",
                 {file_or_empty(src / "golden/regression-set.txt"), "random 40x30 3 0\n"},
                 with(kTextTokens, {"random", "blocks", "flat", "40x30", "0x0", "99999x99999"}),
                 [](const fs::path& p) { (void)util::read_regression_set(p); }});

    // --- mutation lists (mutate --mutations) -----------------------------------------------
    t.push_back({"mutation-list", "mutate --mutations list", "mutations.json",
                 {file_or_empty(src / "mutation/mutations.json")},
                 with(kJsonTokens, {"\"stream\"", "\"mutants\"", "\"pattern\"", "\"size\"", "\"frames\"", "\"seed\"",
                                    "\"id\"", "\"file\"", "\"find\"", "\"replace\"", "\"stage\"", "\"equivalent\""}),
                 [](const fs::path& p) { (void)mutation::load_smoke_list(p); }});

    // --- shard manifests (shard run|merge|status DIR) --------------------------------------
    cluster::Manifest m;
    m.job = "squares";
    m.common = {{"n", 3}};
    m.shards = {{{"first", 0}}, {{"first", 2}}};
    t.push_back({"shard-manifest", "shard run/merge/status DIR/manifest.json", "manifest.json", {m.to_json().dump(2)},
                 with(kJsonTokens, {"\"job\"", "\"common\"", "\"shards\""}),
                 [](const fs::path& p) { (void)cluster::read_manifest(p.parent_path()); }});
    return t;
}

bool run_one(const Target& t, const std::string& bytes, const fs::path& file) {
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) throw std::runtime_error("cannot write the fuzz input " + file.string());
    }
    try {
        t.read(file);
        return true;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        if (msg.find(file.string()) == std::string::npos && msg.find(file.filename().string()) == std::string::npos)
            throw FuzzDefect(t.name + ": the input error does not name the file: " + msg);
        return false;
    } catch (const std::exception& e) {
        throw FuzzDefect(t.name + ": " + typeid(e).name() + " instead of an input error: " + e.what());
    } catch (...) {
        throw FuzzDefect(t.name + ": a non-standard exception instead of an input error");
    }
}

}  // namespace hc::fuzz
