// text.cpp: hashing and the little text formats (util.hpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "model/util/util.hpp"

namespace hc::util {

std::uint64_t fnv1a(std::string_view s, std::uint64_t h) {
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    return h;
}

std::string shell_command_line(const std::string& program, const std::vector<std::string>& args) {
    const auto quoted = [](const std::string& a) {
        const bool plain = !a.empty() && std::all_of(a.begin(), a.end(), [](unsigned char c) {
            return std::isalnum(c) || std::string_view("-_./:=,+@%").find(static_cast<char>(c)) != std::string_view::npos;
        });
        if (plain) return a;
        std::string q = "'";
        for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    std::string out = program;
    for (const auto& a : args) out += " " + quoted(a);
    return out;
}

std::string hex64(std::uint64_t h) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::vector<std::string> split_csv(const std::string& s, char sep) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    for (std::string x; std::getline(ss, x, sep);)
        if (!x.empty()) v.push_back(x);
    return v;
}

namespace {
/// A whole non-negative decimal integer, or throw.
int whole(const std::string& s) {
    std::size_t used = 0;
    const int v = std::stoi(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
    return v;
}
}  // namespace

Range parse_range(const std::string& s, const std::string& what, int open_end) {
    const auto c = s.find(':');
    try {
        if (c == std::string::npos) throw std::invalid_argument("no colon");
        Range r;
        r.first = c == 0 ? 0 : whole(s.substr(0, c));
        r.last = c + 1 == s.size() ? open_end : whole(s.substr(c + 1));
        if (r.first < 0 || r.last <= r.first) throw std::invalid_argument("empty");
        return r;
    } catch (const std::exception&) {
        throw InputError(what + " '" + s + "' is not FIRST:LAST with 0 <= FIRST < LAST (LAST excluded)");
    }
}

std::pair<int, int> parse_size(const std::string& s, const std::string& what) {
    const auto x = s.find('x');
    try {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        const int w = whole(s.substr(0, x)), h = whole(s.substr(x + 1));
        if (w <= 0 || h <= 0) throw std::invalid_argument("not positive");
        return {w, h};
    } catch (const std::exception&) {
        throw InputError(what + " '" + s + "' is not WIDTHxHEIGHT (e.g. 1241x376)");
    }
}

std::string RegressionStream::stem() const {
    return (image.empty() ? pattern : image.stem().string()) + "_" + size();
}
std::string RegressionStream::size() const { return std::to_string(width) + "x" + std::to_string(height); }

std::vector<RegressionStream> read_regression_set(const std::filesystem::path& p) {
    std::istringstream f(read_file(p, "regression set '" + p.string() + "'"));
    std::vector<RegressionStream> v;
    std::string line;
    for (int n = 1; std::getline(f, line); ++n) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        RegressionStream s;
        std::string size, extra;
        const std::string where = p.string() + ":" + std::to_string(n);
        if (!(ss >> s.pattern >> size >> s.frames >> s.idle_every) || s.frames <= 0 || s.idle_every < 0)
            throw InputError(where + ": expected 'pattern WxH frames idle_every' or 'FILE.pgm WxH frames idle_every [breaks=CONFIG.json]'");
        std::tie(s.width, s.height) = parse_size(size, where + ": size");
        const bool is_image = s.pattern.size() > 4 && s.pattern.substr(s.pattern.size() - 4) == ".pgm";
        if (is_image) s.image = p.parent_path() / s.pattern;
        if (ss >> extra) {
            if (!is_image || extra.rfind("breaks=", 0) != 0 || extra.size() == 7)
                throw InputError(where + ": unexpected '" + extra + "' (only an image stream takes breaks=CONFIG.json)");
            s.breaks = p.parent_path() / extra.substr(7);
        }
        if (ss >> extra) throw InputError(where + ": unexpected '" + extra + "'");
        v.push_back(s);
    }
    if (v.empty()) throw InputError("regression set '" + p.string() + "' has no stream");
    return v;
}

std::string AxisRange::gnuplot() const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "[%.6g:%.6g]", lo, hi);
    return buf;
}

AxisRange axis_range(const std::vector<double>& v, double margin, double floor, double ceil, double min_span) {
    double a = 1e300, b = -1e300;
    for (double x : v)
        if (std::isfinite(x)) a = std::min(a, x), b = std::max(b, x);
    if (a > b) {
        if (floor > -1e300 && ceil < 1e300) return {floor, ceil};
        return {0, 1};
    }
    double span = b - a;
    if (span < min_span) {
        const double mid = (a + b) / 2;
        a = mid - min_span / 2;
        b = mid + min_span / 2;
        span = min_span;
    }
    return {std::max(floor, a - margin * span), std::min(ceil, b + margin * span)};
}

}  // namespace hc::util
