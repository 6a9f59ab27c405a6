// cmd_golden.cpp: `harris-cosim golden`: regenerates the committed reference results in
// golden/ from the cycle model, or checks the model against them (--check).
//
// Files (each headed by the command that made it):
//   reads_<pattern>_<WxH>.csv   every read of a regression stream: write,frame,x,y,value
//   maxima_<pattern>_<WxH>.csv  every change of find-max's published maximum: write,max
//   stages_<pattern>_<WxH>.txt  for tiny frames: every observed register after every write
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "driver/host_driver.hpp"
#include "frame_source.hpp"
#include "frames.hpp"
#include "golden_set.hpp"
#include "harris/harris_top.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

std::vector<RegressionStream> read_regression_set(const fs::path& p) {
    std::ifstream f(p);
    if (!f) throw InputError("cannot read regression set '" + p.string() + "'");
    std::vector<RegressionStream> v;
    std::string line;
    int n = 0;
    while (std::getline(f, line)) {
        ++n;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        RegressionStream s;
        std::string size;
        if (!(ss >> s.pattern >> size >> s.frames >> s.idle_every))
            throw InputError(p.string() + ":" + std::to_string(n) + ": expected 'pattern WxH frames idle_every'");
        std::tie(s.width, s.height) = parse_size(size);
        v.push_back(s);
    }
    return v;
}

std::string stream_stem(const RegressionStream& s) {
    return s.pattern + "_" + std::to_string(s.width) + "x" + std::to_string(s.height);
}

namespace {

const char* header_cmd = "harris-cosim golden --out golden";

struct StreamResult {
    std::string reads, maxima, stages;
};

StreamResult run_stream(const RegressionStream& s, bool with_stages) {
    std::vector<Image> frames;
    for (int k = 0; k < s.frames; ++k) frames.push_back(make_pattern(parse_pattern(s.pattern), s.width, s.height, k, 1));
    std::vector<const Image*> ptrs;
    for (const auto& f : frames) ptrs.push_back(&f);
    const Geometry g{s.width, s.height};
    const Formats fm{};
    HostDriver drv(g, ptrs);
    HarrisTop top(g, fm);
    std::ostringstream reads, maxima, stages;
    const std::string what = "# " + std::to_string(s.frames) + " frames of pattern '" + s.pattern + "' (seed 1), " +
                             std::to_string(s.width) + "x" + std::to_string(s.height) + ", thesis formats\n";
    reads << "# made by: " << header_cmd << " (cycle model)\n" << what << "write,frame,x,y,value\n";
    maxima << "# made by: " << header_cmd << " (cycle model)\n" << what << "write,max\n";
    if (with_stages) {
        stages << "# made by: " << header_cmd << " (cycle model)\n" << what
               << "# one line per write: the write index, then every observed register in the order of\n"
               << "# model/harris/observation.hpp obs_layout(), each element's bits in hex\n# fields:";
        for (const auto& f : obs_layout(fm)) stages << " " << f.name << "[" << f.elements() << "]";
        stages << "\n";
    }
    BusEvent ev;
    long last_max = top.find_max().max.value();
    maxima << 0 << ',' << last_max << '\n';
    while (drv.next(ev)) {
        top.write(ev.data);
        if (ev.read)
            reads << top.writes() << ',' << ev.read->frame << ',' << ev.read->x << ',' << ev.read->y << ','
                  << top.corner() << '\n';
        if (top.find_max().max.value() != last_max) {
            last_max = top.find_max().max.value();
            maxima << top.writes() << ',' << last_max << '\n';
        }
        if (with_stages) {
            const FlatObservation fo = flatten(top.observe(), fm);
            stages << top.writes();
            char buf[24];
            for (size_t e = 0; e < fo.bits.size(); ++e) {
                std::snprintf(buf, sizeof buf, " %llx", static_cast<unsigned long long>(fo.bits[e]));
                stages << buf;
            }
            stages << '\n';
        }
    }
    return {reads.str(), maxima.str(), stages.str()};
}

/// The tiny streams whose every register is kept.
std::vector<RegressionStream> tiny_streams() {
    return {{"random", 10, 10, 2, 0}, {"extremes", 11, 11, 2, 0}};
}

std::string read_all(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    if (!f) throw InputError("golden file '" + p.string() + "' is missing");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/// Compares a regenerated file with the committed one; returns a message or "".
std::string compare_file(const fs::path& p, const std::string& now) {
    const std::string was = read_all(p);
    if (was == now) return "";
    std::istringstream a(was), b(now);
    std::string la, lb;
    int line = 0;
    while (true) {
        ++line;
        const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
        if (!ga && !gb) break;
        if (la != lb || ga != gb)
            return p.string() + ":" + std::to_string(line) + ": golden '" + (ga ? la.substr(0, 100) : "<end>") +
                   "' but the model gives '" + (gb ? lb.substr(0, 100) : "<end>") + "'";
    }
    return p.string() + ": differs";
}

}  // namespace

void add_golden_command(CLI::App& app) {
    struct Opts {
        std::string out = "golden";
        std::string set;
        bool check = false;
    };
    auto o = std::make_shared<Opts>();
    CLI::App* cmd = app.add_subcommand(
        "golden",
        "Regenerate the golden reference results from the cycle model (a deliberate act: review the diff),\n"
        "or with --check compare the model with the committed files.");
    cmd->add_option("--out", o->out, "golden directory")->capture_default_str();
    cmd->add_option("--set", o->set, "regression-set file (default <out>/regression-set.txt)");
    cmd->add_flag("--check", o->check, "compare instead of writing; exit 1 on any difference");
    cmd->callback([o]() {
        const fs::path dir = o->out;
        const auto set = read_regression_set(o->set.empty() ? dir / "regression-set.txt" : fs::path(o->set));
        std::vector<std::pair<fs::path, std::string>> files;
        for (const auto& s : set) {
            const StreamResult r = run_stream(s, false);
            files.emplace_back(dir / ("reads_" + stream_stem(s) + ".csv"), r.reads);
            files.emplace_back(dir / ("maxima_" + stream_stem(s) + ".csv"), r.maxima);
        }
        for (const auto& s : tiny_streams())
            files.emplace_back(dir / ("stages_" + stream_stem(s) + ".txt"), run_stream(s, true).stages);
        int bad = 0;
        for (const auto& [p, text] : files) {
            if (o->check) {
                const std::string msg = compare_file(p, text);
                if (!msg.empty()) {
                    std::fprintf(stderr, "golden mismatch: %s\n", msg.c_str());
                    ++bad;
                }
            } else {
                write_file_atomic(p, text);
            }
        }
        std::printf("harris-cosim golden: %zu files %s%s\n", files.size(), o->check ? "checked" : "written to ",
                    o->check ? (bad ? (", " + std::to_string(bad) + " differ").c_str() : ", all equal") : dir.c_str());
        if (bad) throw CLI::RuntimeError(1);
    });
}

}  // namespace hc::tools
