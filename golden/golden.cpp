// golden.cpp: see golden.hpp.
#include "golden/golden.hpp"

#include <cstdio>
#include <sstream>

#include "cosim/corners/corners.hpp"
#include "model/harris/observation.hpp"

namespace fs = std::filesystem;

namespace hc::golden {

namespace {

const char* header_cmd = "harris-cosim golden --out golden";

struct StreamResult {
    std::string reads, maxima, stages;
};

StreamResult run_stream(const util::RegressionStream& s, bool with_stages) {
    const std::vector<Image> frames = stream_frames(s);
    const Geometry g{s.width, s.height};
    const Formats fm{};
    corners::DesignStream design(g, fm, static_cast<int>(frames.size()), [&frames](int k) {
        return std::shared_ptr<const Image>(std::shared_ptr<const Image>{}, &frames.at(static_cast<std::size_t>(k)));   // not owned
    });
    const HarrisTop& top = design.model();
    std::ostringstream reads, maxima, stages;
    const std::string what = "# " + std::to_string(s.frames) + " frames of " +
                             (s.image.empty() ? "pattern '" + s.pattern + "' (seed 1), " : "image '" + s.pattern + "', ") +
                             s.size() + ", thesis formats\n";
    reads << "# made by: " << header_cmd << " (cycle model)\n" << what << "write,frame,x,y,value\n";
    maxima << "# made by: " << header_cmd << " (cycle model)\n" << what << "write,max\n";
    if (with_stages) {
        stages << "# made by: " << header_cmd << " (cycle model)\n" << what
               << "# one line per write: the write index, then every observed register in the order of\n"
               << "# model/harris/observation.hpp obs_layout(), each element's bits in hex\n# fields:";
        for (const auto& f : obs_layout(fm)) stages << " " << f.name << "[" << f.elements() << "]";
        stages << "\n";
    }
    struct Hooks : BusHooks {
        const HarrisTop& top;
        const Formats& fm;
        bool with_stages;
        std::ostringstream &reads, &maxima, &stages;
        long last_max;
        void after(const BusEvent&) {
            if (top.find_max().max.value() != last_max) {
                last_max = top.find_max().max.value();
                maxima << top.writes() << ',' << last_max << '\n';
            }
            if (!with_stages) return;
            const FlatObservation fo = flatten(top.observe(), fm);
            stages << top.writes();
            char buf[24];
            for (size_t e = 0; e < fo.bits.size(); ++e) {
                std::snprintf(buf, sizeof buf, " %llx", static_cast<unsigned long long>(fo.bits[e]));
                stages << buf;
            }
            stages << '\n';
        }
        void read(const BusEvent& ev, std::uint32_t value, const std::vector<Corner>&) {
            reads << top.writes() << ',' << ev.read->frame << ',' << ev.read->x << ',' << ev.read->y << ',' << value << '\n';
        }
    } hooks{{}, top, fm, with_stages, reads, maxima, stages, top.find_max().max.value()};
    maxima << 0 << ',' << hooks.last_max << '\n';
    design.run(hooks);
    return {reads.str(), maxima.str(), stages.str()};
}

/// The tiny streams whose every register is kept.
std::vector<util::RegressionStream> tiny_streams() {
    return {{"random", 10, 10, 2, 0, {}, {}}, {"extremes", 11, 11, 2, 0, {}, {}}};
}

}  // namespace

std::vector<Image> stream_frames(const util::RegressionStream& s) {
    std::vector<Image> frames;
    if (s.image.empty()) {
        for (int k = 0; k < s.frames; ++k) frames.push_back(make_pattern(parse_pattern(s.pattern), s.width, s.height, k, 1));
        return frames;
    }
    const Image im = read_pgm(s.image.string());
    if (im.width != s.width || im.height != s.height)
        throw InputError("regression stream image '" + s.image.string() + "' is " + std::to_string(im.width) + "x" +
                         std::to_string(im.height) + ", the set says " + s.size());
    frames.assign(static_cast<size_t>(s.frames), im);
    return frames;
}

std::vector<GoldenFile> golden_files(const std::vector<util::RegressionStream>& set, const fs::path& dir) {
    std::vector<GoldenFile> files;
    for (const auto& s : set) {
        StreamResult r = run_stream(s, false);
        files.push_back({dir / ("reads_" + s.stem() + ".csv"), std::move(r.reads)});
        files.push_back({dir / ("maxima_" + s.stem() + ".csv"), std::move(r.maxima)});
    }
    for (const auto& s : tiny_streams()) files.push_back({dir / ("stages_" + s.stem() + ".txt"), run_stream(s, true).stages});
    return files;
}

std::string compare_golden(const GoldenFile& now) {
    const std::string was = util::read_file(now.path, "golden file '" + now.path.string() + "'");
    if (was == now.text) return "";
    std::istringstream a(was), b(now.text);
    std::string la, lb;
    for (int line = 1;; ++line) {
        const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
        if (!ga && !gb) break;
        if (la != lb || ga != gb)
            return now.path.string() + ":" + std::to_string(line) + ": golden '" + (ga ? la.substr(0, 100) : "<end>") +
                   "' but the model gives '" + (gb ? lb.substr(0, 100) : "<end>") + "'";
    }
    return now.path.string() + ": differs";
}

}  // namespace hc::golden
