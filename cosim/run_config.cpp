#include "cosim/run_config.hpp"

#include "model/harris/formats_json.hpp"
#include "model/util/errors.hpp"

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace hc::cosim {

using nlohmann::json;

// RunConfig's fields but its geometry and formats, one key a field by its name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RunConfig, frames_file, frame_names, backend, keep_going, compare_all, idle_every,
                                   max_writes, post_mismatch, pre_mismatch, vcd_file, summary_file, reads_file, progress)

std::string to_json(const RunConfig& c) {
    json j = c;
    j["geometry"] = {{"width", c.geometry.width}, {"height", c.geometry.height}};
    j["formats"] = fields_to_json(c.formats, format_fields());
    return j.dump(2);
}

RunConfig run_config_from_json(const std::string& text) {
    try {
        const json j = json::parse(text);
        RunConfig c;
        c.geometry.width = j.at("geometry").at("width").get<int>();
        c.geometry.height = j.at("geometry").at("height").get<int>();
        c.formats = formats_from_json(j.at("formats"), "run configuration formats");
        from_json(j, c);
        c.geometry.validate();
        return c;
    } catch (const json::exception& e) {
        throw InternalError(std::string("run configuration: ") + e.what());
    } catch (const InputError& e) {
        throw InternalError(std::string("run configuration: ") + e.what());
    }
}

std::string to_json(const Summary& s) {
    json stages = json::object();
    for (const auto& st : s.stages)
        stages[st.stage] = {{"elements_compared_per_cycle", st.elements_compared_per_cycle},
                            {"mismatching_cycles", st.mismatching_cycles},
                            {"mismatching_elements", st.mismatching_elements},
                            {"first_mismatching_stage_cycles", st.first_mismatching_stage_cycles}};
    json frames = json::array();
    for (size_t k = 0; k < s.frame_names.size(); ++k)
        frames.push_back({{"index", k}, {"name", s.frame_names[k]},
                          {"corners_read", k < s.corners_per_frame.size() ? s.corners_per_frame[k] : 0}});
    json j = {{"backend", s.backend},
              {"geometry", {{"width", s.geometry.width}, {"height", s.geometry.height}}},
              {"formats", fields_to_json(s.formats, format_fields())},
              {"frames", frames},
              {"complete", s.complete},
              {"writes", s.writes},
              {"writes_in_stream", s.writes_in_stream},
              {"idle_cycles", s.idle_cycles},
              {"cycles", s.cycles},
              {"reads", s.reads},
              {"read_mismatches", s.read_mismatches},
              {"corners", s.corners},
              {"compare", s.compare_all ? "all" : "reads"},
              {"signals_compared_per_cycle", s.signals_compared_per_cycle},
              {"bits_compared_per_cycle", s.bits_compared_per_cycle},
              {"stages", stages},
              {"mismatches", {{"cycles", s.mismatching_cycles},
                              {"elements", s.mismatching_elements},
                              {"metavalue_elements", s.metavalue_elements}}},
              {"wall_seconds", s.wall_seconds},
              {"cycles_per_second", s.cycles_per_second},
              {"status", s.mismatching_cycles > 0 ? "mismatch" : "pass"}};
    if (s.first_mismatch)
        j["first_mismatch"] = {{"write", s.first_mismatch->write}, {"stage", s.first_mismatch->stage},
                               {"signal", s.first_mismatch->signal}, {"report", s.first_mismatch->report},
                               {"vcd", s.first_mismatch->vcd}};
    return j.dump(2) + "\n";
}

Summary summary_from_json(const std::string& text) {
    try {
        const json j = json::parse(text);
        Summary s;
        s.backend = j.at("backend").get<std::string>();
        s.geometry.width = j.at("geometry").at("width").get<int>();
        s.geometry.height = j.at("geometry").at("height").get<int>();
        s.formats = formats_from_json(j.at("formats"), "summary formats");
        for (const auto& f : j.at("frames")) {
            s.frame_names.push_back(f.at("name").get<std::string>());
            s.corners_per_frame.push_back(f.at("corners_read").get<long>());
        }
        s.complete = j.at("complete").get<bool>();
        s.writes = j.at("writes").get<long>();
        s.writes_in_stream = j.at("writes_in_stream").get<long>();
        s.idle_cycles = j.at("idle_cycles").get<long>();
        s.cycles = j.at("cycles").get<long>();
        s.reads = j.at("reads").get<long>();
        s.read_mismatches = j.at("read_mismatches").get<long>();
        s.corners = j.at("corners").get<long>();
        s.compare_all = j.at("compare").get<std::string>() == "all";
        s.signals_compared_per_cycle = j.at("signals_compared_per_cycle").get<long>();
        s.bits_compared_per_cycle = j.at("bits_compared_per_cycle").get<long>();
        for (const auto& [name, v] : j.at("stages").items())
            s.stages.push_back({name, v.at("elements_compared_per_cycle").get<long>(),
                                v.at("mismatching_cycles").get<long>(), v.at("mismatching_elements").get<long>(),
                                v.at("first_mismatching_stage_cycles").get<long>()});
        s.mismatching_cycles = j.at("mismatches").at("cycles").get<long>();
        s.mismatching_elements = j.at("mismatches").at("elements").get<long>();
        s.metavalue_elements = j.at("mismatches").at("metavalue_elements").get<long>();
        s.wall_seconds = j.at("wall_seconds").get<double>();
        s.cycles_per_second = j.at("cycles_per_second").get<double>();
        if (j.contains("first_mismatch")) {
            const json& f = j.at("first_mismatch");
            s.first_mismatch = FirstMismatch{f.at("write").get<long>(), f.at("stage").get<std::string>(),
                                             f.at("signal").get<std::string>(), f.at("report").get<std::string>(),
                                             f.at("vcd").get<std::string>()};
        }
        return s;
    } catch (const json::exception& e) {
        throw InternalError(std::string("co-simulation summary: ") + e.what());
    } catch (const InputError& e) {
        throw InternalError(std::string("co-simulation summary: ") + e.what());
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
