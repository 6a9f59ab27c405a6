// sweep_config.cpp: see sweep_config.hpp.
#include "sweep/sweep_config.hpp"

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "mapping/landmarks/landmarks.hpp"
#include "model/harris/formats_json.hpp"
#include "model/util/util.hpp"

namespace hc::sweep {

using json = nlohmann::json;

namespace {

using Field = FormatField;

const Field* find_key(const std::string& k) {
    for (const auto& f : format_fields())
        if (k == f.name) return &f;
    return nullptr;
}

/// Position of a field in the table (the struct's order).
std::ptrdiff_t index_of(const Field* f) { return f - format_fields().data(); }

[[noreturn]] void fail(const std::string& what, const std::string& where, const std::string& msg) {
    throw InputError(what + ": " + where + ": " + msg);
}

int int_value(const json& v, const std::string& what, const std::string& where) {
    if (!v.is_number_integer()) fail(what, where, "must be an integer, not " + v.dump());
    const auto x = v.get<long long>();
    if (x < -1000000 || x > 1000000) fail(what, where, "value " + v.dump() + " out of range");
    return static_cast<int>(x);
}

/// Applies the Formats keys of `obj` to `f` (the one reader, model/harris/formats_json.hpp).
void apply(const json& obj, Formats& f, const std::string& what, const std::string& where) {
    apply_fields(obj, f, format_fields(), what + ": " + where);
}

void check_keys(const json& obj, const std::set<std::string>& allowed, const std::string& what,
                const std::string& where) {
    for (const auto& [k, v] : obj.items())
        if (!allowed.count(k)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail(what, where, "unknown key '" + k + "' (allowed: " + list + ")");
        }
}

std::string string_value(const json& v, const std::string& what, const std::string& where) {
    if (!v.is_string()) fail(what, where, "must be a string, not " + v.dump());
    return v.get<std::string>();
}

/// The points of one grid object: the cartesian product of its value lists over `base`.
void expand_grid(const json& g, const Formats& base, const std::string& what, const std::string& where,
                 std::vector<std::pair<Config, std::string>>& out) {
    if (!g.is_object() || g.empty()) fail(what, where, "must be a non-empty object {\"key\": [values...]}");
    std::vector<std::pair<const Field*, std::vector<int>>> axes;
    for (const auto& [k, v] : g.items()) {
        const Field* key = find_key(k);
        if (!key) fail(what, where, "unknown key '" + k + "' (format keys: " + field_names(format_fields()) + ")");
        if (!v.is_array() || v.empty()) fail(what, where + "." + k, "must be a non-empty list of integers");
        std::vector<int> vals;
        for (size_t i = 0; i < v.size(); ++i)
            vals.push_back(int_value(v[i], what, where + "." + k + "[" + std::to_string(i) + "]"));
        axes.emplace_back(key, vals);
    }
    // keep the struct's key order in names whatever order the JSON object had
    std::sort(axes.begin(), axes.end(), [](const auto& a, const auto& b) { return index_of(a.first) < index_of(b.first); });
    size_t total = 1;
    for (const auto& a : axes) {
        total *= a.second.size();
        if (total > 10000) fail(what, where, "grid has more than 10000 points");
    }
    for (size_t n = 0; n < total; ++n) {
        Config c{"", base};
        size_t rest = n;
        for (auto it = axes.rbegin(); it != axes.rend(); ++it) {   // last axis varies fastest
            const int v = it->second[rest % it->second.size()];
            rest /= it->second.size();
            c.formats.*(it->first->member) = v;
        }
        for (const auto& a : axes) {
            if (!c.name.empty()) c.name += ',';
            c.name.append(a.first->name).append("=").append(std::to_string(c.formats.*(a.first->member)));
        }
        out.emplace_back(c, where + " point " + c.name);
    }
}

/// The configurations of "configs" and "grid" over `base`, each with where it came from.
std::vector<std::pair<Config, std::string>> spec_entries(const json& j, const Formats& base, const std::string& what) {
    std::vector<std::pair<Config, std::string>> entries;   // config, where it came from
    if (j.contains("configs")) {
        const json& cs = j["configs"];
        if (!cs.is_array()) throw InputError(what + ": configs: must be a list of objects");
        for (size_t i = 0; i < cs.size(); ++i) {
            const std::string where = "configs[" + std::to_string(i) + "]";
            Config c{"", base};
            apply(cs[i], c.formats, what, where);
            c.name = cs[i].contains("name") ? string_value(cs[i]["name"], what, where + ".name")
                                            : describe_difference(c.formats);
            if (c.name.empty() || c.name.find_first_of(",\n\"|") != std::string::npos)
                if (cs[i].contains("name"))
                    fail(what, where + ".name", "must be non-empty without ',', '|', '\"' or newlines");
            entries.emplace_back(c, where + " (\"" + c.name + "\")");
        }
    }
    if (j.contains("grid")) {
        const json& g = j["grid"];
        if (g.is_array()) {
            for (size_t i = 0; i < g.size(); ++i) expand_grid(g[i], base, what, "grid[" + std::to_string(i) + "]", entries);
        } else {
            expand_grid(g, base, what, "grid", entries);
        }
    }
    return entries;
}

/// The entries validated into s.configs (equal formats merged, equal names refused), with
/// the thesis's configuration added when no entry has its formats.
void add_configs(SweepSpec& s, std::vector<std::pair<Config, std::string>>& entries, const std::string& what) {
    std::map<std::string, std::string> names;   // name -> where
    for (auto& [c, where] : entries) {
        try {
            c.formats.validate();
        } catch (const std::invalid_argument& e) {
            fail(what, where, e.what());
        }
        bool dup = false;
        for (const auto& d : s.configs)
            if (d.formats == c.formats) {
                s.notes.push_back(where + " has the same formats as \"" + d.name + "\": merged into it");
                dup = true;
                break;
            }
        if (dup) continue;
        if (names.count(c.name)) fail(what, where, "name \"" + c.name + "\" already used by " + names[c.name]);
        names[c.name] = where;
        s.configs.push_back(c);
    }
    bool has_thesis = false;
    for (const auto& c : s.configs) has_thesis |= c.formats == Formats{};
    if (!has_thesis) {
        if (names.count("thesis")) fail(what, names["thesis"], "the name \"thesis\" is reserved for the thesis's formats");
        s.configs.push_back({"thesis", Formats{}});
        s.notes.push_back("the thesis configuration was added as the yardstick");
    }
}

void parse_cost(const json& c, SweepSpec& s, const std::string& what) {
    if (!c.is_object()) fail(what, "cost", "must be an object");
    check_keys(c, {"img_width", "img_height"}, what, "cost");
    if (c.contains("img_width")) s.cost_geometry.width = int_value(c["img_width"], what, "cost.img_width");
    if (c.contains("img_height")) s.cost_geometry.height = int_value(c["img_height"], what, "cost.img_height");
    try {
        s.cost_geometry.validate();
    } catch (const std::invalid_argument& e) {
        fail(what, "cost", e.what());
    }
}

void parse_trust(const json& t, SweepSpec& s, const std::string& what) {
    if (!t.is_object()) fail(what, "trust", "must be an object");
    check_keys(t, {"rtl", "verilator_pairs", "verilator_gate"}, what, "trust");
    if (t.contains("rtl")) {
        if (!t["rtl"].is_boolean()) fail(what, "trust.rtl", "must be true or false");
        s.trust.rtl = t["rtl"].get<bool>();
    }
    if (t.contains("verilator_pairs")) s.trust.verilator_pairs = string_value(t["verilator_pairs"], what, "trust.verilator_pairs");
    if (t.contains("verilator_gate")) {
        if (!t["verilator_gate"].is_boolean()) fail(what, "trust.verilator_gate", "must be true or false");
        s.trust.verilator_gate = t["verilator_gate"].get<bool>();
    }
}

void parse_data(const json& d, SweepSpec& s, const std::string& what) {
    if (!d.is_object()) fail(what, "data", "must be an object");
    check_keys(d, {"sequence", "pairs"}, what, "data");
    if (d.contains("sequence")) s.sequence = string_value(d["sequence"], what, "data.sequence");
    if (d.contains("pairs")) s.pairs = string_value(d["pairs"], what, "data.pairs");
}

void parse_trajectory(const json& t, SweepSpec& s, const std::string& what) {
    if (t.is_boolean()) {
        s.trajectory.enabled = t.get<bool>();
        return;
    }
    if (!t.is_object()) fail(what, "trajectory", "must be a boolean or an object {\"sequence\": \"01\", \"descriptor\": \"orb\"}");
    check_keys(t, {"sequence", "descriptor"}, what, "trajectory");
    s.trajectory.enabled = true;
    if (t.contains("sequence")) s.trajectory.sequence = string_value(t["sequence"], what, "trajectory.sequence");
    if (t.contains("descriptor")) s.trajectory.descriptor = string_value(t["descriptor"], what, "trajectory.descriptor");
    try {
        landmarks::parse_descriptor(s.trajectory.descriptor);
    } catch (const hc::InputError& e) {
        fail(what, "trajectory.descriptor", e.what());
    }
}

void parse_landmarks(const json& l, SweepSpec& s, const std::string& what) {
    if (l.is_boolean()) {
        s.landmarks.enabled = l.get<bool>();
    } else {
        if (!l.is_object()) fail(what, "landmarks", "must be false or an object {\"scenes\": [...], \"g\": 16, \"h\": 3}");
        check_keys(l, {"scenes", "g", "h"}, what, "landmarks");
        if (l.contains("scenes")) {
            const json& sc = l["scenes"];
            if (!sc.is_array() || sc.empty()) fail(what, "landmarks.scenes", "must be a non-empty list of scene names");
            s.landmarks.scenes.clear();
            for (size_t i = 0; i < sc.size(); ++i)
                s.landmarks.scenes.push_back(string_value(sc[i], what, "landmarks.scenes[" + std::to_string(i) + "]"));
        }
        if (l.contains("g")) s.landmarks.g = int_value(l["g"], what, "landmarks.g");
        if (l.contains("h")) s.landmarks.h = int_value(l["h"], what, "landmarks.h");
        try {
            landmarks::validate(landmarks::GridParams{s.landmarks.g, s.landmarks.h});
        } catch (const hc::InputError& e) {
            fail(what, "landmarks", e.what());
        }
    }
}

}  // namespace

SweepSpec parse_sweep_spec(const std::string& text, const std::string& what) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        throw InputError(what + ": not valid JSON: " + e.what());
    }
    if (!j.is_object()) throw InputError(what + ": the sweep spec must be a JSON object");
    check_keys(j, {"name", "base", "configs", "grid", "cost", "trust", "data", "landmarks", "trajectory", "comment"}, what,
               "top level");
    SweepSpec s;
    if (j.contains("name")) s.name = string_value(j["name"], what, "name");
    Formats base;
    if (j.contains("base")) apply(j["base"], base, what, "base");

    std::vector<std::pair<Config, std::string>> entries = spec_entries(j, base, what);
    if (entries.empty()) throw InputError(what + ": no configuration: give \"configs\" and/or \"grid\"");

    add_configs(s, entries, what);
    if (j.contains("cost")) parse_cost(j["cost"], s, what);
    if (j.contains("trust")) parse_trust(j["trust"], s, what);
    if (j.contains("data")) parse_data(j["data"], s, what);
    if (j.contains("landmarks")) parse_landmarks(j["landmarks"], s, what);
    if (j.contains("trajectory")) parse_trajectory(j["trajectory"], s, what);
    return s;
}

SweepSpec load_sweep_spec(const std::filesystem::path& p) {
    const std::string what = "sweep spec '" + p.string() + "'";
    return parse_sweep_spec(util::read_file(p, what), what);
}

}  // namespace hc::sweep
