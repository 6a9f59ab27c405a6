#include "run_config.hpp"

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace hc::cosim {

using nlohmann::json;

namespace {
json formats_json(const Formats& f) {
    return {{"sobel_w", f.sobel_w},   {"m_prod_w", f.m_prod_w},     {"m_drop", f.m_drop},
            {"bf_sum_w", f.bf_sum_w}, {"bf_drop", f.bf_drop},       {"resp_w", f.resp_w},
            {"ktr_w", f.ktr_w},       {"k_shift1", f.k_shift1},     {"k_shift2", f.k_shift2},
            {"thr_shift1", f.thr_shift1}, {"thr_shift2", f.thr_shift2}};
}

Formats formats_of(const json& j) {
    if (!j.is_object()) throw std::invalid_argument("formats must be a JSON object");
    Formats f;
    const std::pair<const char*, int*> keys[] = {
        {"sobel_w", &f.sobel_w},   {"m_prod_w", &f.m_prod_w},     {"m_drop", &f.m_drop},
        {"bf_sum_w", &f.bf_sum_w}, {"bf_drop", &f.bf_drop},       {"resp_w", &f.resp_w},
        {"ktr_w", &f.ktr_w},       {"k_shift1", &f.k_shift1},     {"k_shift2", &f.k_shift2},
        {"thr_shift1", &f.thr_shift1}, {"thr_shift2", &f.thr_shift2}};
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (auto [name, field] : keys)
            if (it.key() == name) {
                if (!it.value().is_number_integer())
                    throw std::invalid_argument(std::string("formats: '") + name + "' must be an integer");
                *field = it.value().get<int>();
                known = true;
            }
        if (!known && it.key() != "name")
            throw std::invalid_argument("formats: unknown key '" + it.key() + "'");
    }
    f.validate();
    return f;
}
}  // namespace

std::string formats_to_json(const Formats& f) { return formats_json(f).dump(2); }

Formats formats_from_json(const std::string& text) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        throw std::invalid_argument(std::string("formats: not JSON: ") + e.what());
    }
    return formats_of(j);
}

std::string to_json(const RunConfig& c) {
    json j = {{"geometry", {{"width", c.geometry.width}, {"height", c.geometry.height}}},
              {"formats", formats_json(c.formats)},
              {"frames_file", c.frames_file},
              {"frame_names", c.frame_names},
              {"backend", c.backend},
              {"keep_going", c.keep_going},
              {"compare_all", c.compare_all},
              {"idle_every", c.idle_every},
              {"max_writes", c.max_writes},
              {"post_mismatch", c.post_mismatch},
              {"pre_mismatch", c.pre_mismatch},
              {"vcd_file", c.vcd_file},
              {"summary_file", c.summary_file},
              {"reads_file", c.reads_file},
              {"progress", c.progress}};
    return j.dump(2);
}

RunConfig run_config_from_json(const std::string& text) {
    try {
        const json j = json::parse(text);
        RunConfig c;
        c.geometry.width = j.at("geometry").at("width").get<int>();
        c.geometry.height = j.at("geometry").at("height").get<int>();
        c.formats = formats_of(j.at("formats"));
        c.frames_file = j.at("frames_file").get<std::string>();
        c.frame_names = j.at("frame_names").get<std::vector<std::string>>();
        c.backend = j.at("backend").get<std::string>();
        c.keep_going = j.at("keep_going").get<bool>();
        c.compare_all = j.at("compare_all").get<bool>();
        c.idle_every = j.at("idle_every").get<int>();
        c.max_writes = j.at("max_writes").get<long>();
        c.post_mismatch = j.at("post_mismatch").get<int>();
        c.pre_mismatch = j.at("pre_mismatch").get<int>();
        c.vcd_file = j.at("vcd_file").get<std::string>();
        c.summary_file = j.at("summary_file").get<std::string>();
        c.reads_file = j.at("reads_file").get<std::string>();
        c.progress = j.at("progress").get<bool>();
        c.geometry.validate();
        return c;
    } catch (const json::exception& e) {
        throw std::invalid_argument(std::string("run configuration: ") + e.what());
    }
}

namespace {
constexpr char magic[8] = {'H', 'C', 'F', 'R', 'A', 'M', 'E', 'S'};
}

void write_frames(const std::filesystem::path& p, const std::vector<Image>& frames) {
    std::ofstream f(p, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write frame file '" + p.string() + "'");
    const std::int32_t hdr[3] = {static_cast<std::int32_t>(frames.size()),
                                 frames.empty() ? 0 : frames[0].width,
                                 frames.empty() ? 0 : frames[0].height};
    f.write(magic, sizeof magic);
    f.write(reinterpret_cast<const char*>(hdr), sizeof hdr);
    for (const auto& im : frames) {
        if (im.width != hdr[1] || im.height != hdr[2])
            throw std::invalid_argument("frames of different sizes in one stream");
        f.write(reinterpret_cast<const char*>(im.pixels.data()), static_cast<std::streamsize>(im.pixels.size()));
    }
    if (!f) throw std::runtime_error("cannot write frame file '" + p.string() + "'");
}

std::vector<Image> read_frames(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read frame file '" + p.string() + "'");
    char m[8];
    std::int32_t hdr[3];
    f.read(m, sizeof m);
    f.read(reinterpret_cast<char*>(hdr), sizeof hdr);
    if (!f || std::memcmp(m, magic, sizeof m) != 0 || hdr[0] <= 0 || hdr[1] <= 0 || hdr[2] <= 0)
        throw std::runtime_error("'" + p.string() + "' is not a frame file");
    std::vector<Image> frames;
    for (int k = 0; k < hdr[0]; ++k) {
        Image im(hdr[1], hdr[2]);
        f.read(reinterpret_cast<char*>(im.pixels.data()), static_cast<std::streamsize>(im.pixels.size()));
        if (!f) throw std::runtime_error("frame file '" + p.string() + "' is truncated");
        frames.push_back(std::move(im));
    }
    return frames;
}

}  // namespace hc::cosim
