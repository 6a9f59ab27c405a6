// frame_flags_test.cpp: the frame-source flags mean the same in every command. One table states
// each flag's meaning (a count of frames, a range of stereo pairs, a text, a list of images) and the commands
// that must have it; every command of harris-cosim (tools/commands.hpp add_commands) is then
// parsed in-process, its callbacks replaced by no-ops, with each of these flags it has: the
// values the meaning accepts give the typed value, the others are refused, and no flag has a
// second name.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "model/util/util.hpp"
#include "tools/commands.hpp"

namespace {

enum class Meaning { frame_count, pair_range, text, image_list };

struct Flag {
    std::string name;
    Meaning meaning;
    std::set<std::string> required_in;   ///< commands that must have it
};

const std::vector<Flag>& table() {
    static const std::vector<Flag> t{
        {"--frames", Meaning::frame_count, {"rtl", "model", "verilate", "eval"}},
        {"--pairs", Meaning::pair_range, {"rtl", "model", "verilate", "eval", "landmarks", "slam"}},
        {"--sequence", Meaning::text, {"rtl", "model", "verilate", "eval", "landmarks"}},
        {"--sequences", Meaning::text, {"verilate", "eval", "slam"}},
        {"--kitti", Meaning::text, {"rtl", "model", "verilate", "eval", "landmarks", "slam"}},
        {"--data", Meaning::text, {"rtl", "model", "verilate", "eval", "landmarks", "slam"}},
        {"--calib", Meaning::text, {"landmarks", "slam"}},
        {"--left", Meaning::image_list, {"landmarks", "slam", "calibrate"}},
        {"--right", Meaning::image_list, {"landmarks", "slam", "calibrate"}},
    };
    return t;
}

/// harris-cosim's commands, as main registers them, with callbacks that do nothing and no
/// option required (so that one flag parses alone).
std::unique_ptr<CLI::App> quiet_app() {
    auto app = std::make_unique<CLI::App>("harris-cosim");
    hc::tools::add_commands(*app);
    std::vector<CLI::App*> todo = app->get_subcommands([](const CLI::App*) { return true; });
    while (!todo.empty()) {
        CLI::App* c = todo.back();
        todo.pop_back();
        c->callback([] {});
        for (CLI::Option* o : c->get_options()) o->required(false);
        for (CLI::App* s : c->get_subcommands([](const CLI::App*) { return true; })) todo.push_back(s);
    }
    return app;
}

/// Every command by its path (e.g. "slam", "shard run").
std::vector<std::string> command_paths() {
    const auto app = quiet_app();
    std::vector<std::string> out;
    std::vector<std::pair<std::string, CLI::App*>> todo;
    for (CLI::App* s : app->get_subcommands([](const CLI::App*) { return true; })) todo.emplace_back(s->get_name(), s);
    while (!todo.empty()) {
        const auto [path, c] = todo.back();
        todo.pop_back();
        out.push_back(path);
        for (CLI::App* s : c->get_subcommands([](const CLI::App*) { return true; }))
            todo.emplace_back(path + " " + s->get_name(), s);
    }
    return out;
}

/// The command `path` of `app`.
CLI::App* command(CLI::App& app, const std::string& path) {
    CLI::App* c = &app;
    for (const std::string& name : hc::util::split_csv(path, ' ')) c = c->get_subcommand(name);
    return c;
}

/// `path flag value` parsed by a fresh app; the option parsed, for its typed value.
struct Parsed {
    std::unique_ptr<CLI::App> app;
    const CLI::Option* option = nullptr;
};
Parsed parse(const std::string& path, const std::string& flag, const std::string& value) {
    Parsed p{quiet_app()};
    p.app->parse(path + " " + flag + " " + value, false);
    p.option = command(*p.app, path)->get_option(flag);
    return p;
}

}  // namespace

TEST_CASE("the table's commands exist", "[cli]") {
    const std::vector<std::string> paths = command_paths();
    for (const std::string& c : {"rtl", "model", "verilate", "eval", "landmarks", "slam", "sweep", "mutate"})
        CHECK(std::find(paths.begin(), paths.end(), c) != paths.end());
}

TEST_CASE("each frame-source flag is where the table says and has one name", "[cli]") {
    const auto app = quiet_app();
    for (const std::string& path : command_paths()) {
        const CLI::App* c = command(*app, path);
        for (const Flag& f : table()) {
            INFO(path << " " << f.name);
            const CLI::Option* o = c->get_option_no_throw(f.name);
            if (f.required_in.count(path)) CHECK(o != nullptr);
            if (!o) continue;
            CHECK(o->get_lnames() == std::vector<std::string>{f.name.substr(2)});
            CHECK(o->get_snames().empty());
            CHECK(o->get_type_size() == 1);   // values, not a flag
            CHECK((o->get_expected_max() > 1) == (f.meaning == Meaning::image_list));   // a list takes several
        }
        // no other option answers to one of the table's names (an alias of another option)
        for (const CLI::Option* o : c->get_options())
            for (const Flag& f : table())
                if (o->check_lname(f.name.substr(2))) {
                    INFO(path << ": " << o->get_name());
                    CHECK(o->get_lnames().size() == 1);
                }
    }
}

TEST_CASE("each frame-source flag takes the values of its meaning in every command", "[cli]") {
    for (const std::string& path : command_paths()) {
        for (const Flag& f : table()) {
            if (!command(*quiet_app(), path)->get_option_no_throw(f.name)) continue;
            INFO(path << " " << f.name);
            switch (f.meaning) {
            case Meaning::frame_count:
                CHECK(parse(path, f.name, "3").option->as<int>() == 3);
                CHECK(parse(path, f.name, "1").option->as<int>() == 1);
                for (const char* bad : {"2:5", "0", "x", "-1"}) {
                    INFO(bad);
                    CHECK_THROWS_AS(parse(path, f.name, bad), CLI::ParseError);
                }
                break;
            case Meaning::pair_range: {
                const hc::util::Range r = hc::util::parse_range(parse(path, f.name, "2:5").option->as<std::string>(), f.name);
                CHECK(r.first == 2);
                CHECK(r.last == 5);
                CHECK(hc::util::parse_range(parse(path, f.name, "3:").option->as<std::string>(), f.name).first == 3);
                for (const char* bad : {"5:2", "x", "3", "2:2"}) {
                    INFO(bad);
                    CHECK_THROWS_AS(parse(path, f.name, bad), CLI::ParseError);
                }
                CHECK_THROWS_WITH(parse(path, f.name, "5:2"),
                                  Catch::Contains("--pairs '5:2' is not FIRST:LAST with 0 <= FIRST < LAST"));
                break;
            }
            case Meaning::text:
                CHECK(parse(path, f.name, "07").option->as<std::string>() == "07");
                break;
            case Meaning::image_list:
                CHECK(parse(path, f.name, "a.png 'b*.png' dir").option->as<std::vector<std::string>>() ==
                      std::vector<std::string>{"a.png", "b*.png", "dir"});
                break;
            }
        }
    }
}

TEST_CASE("a report's command line is the one typed, less the sharding flags, and its settings name every other flag",
          "[cli]") {
    auto app = quiet_app();
    const std::vector<std::string> typed{"harris-cosim", "slam", "--resume", "--sequences", "01", "--jobs", "2",
                                         "--no-vo-level", "--run-dir=r", "--out", "a b"};
    std::vector<char*> argv;
    for (const std::string& a : typed) argv.push_back(const_cast<char*>(a.c_str()));
    hc::tools::set_command_line(static_cast<int>(argv.size()), argv.data());
    app->parse(static_cast<int>(argv.size()), argv.data());
    const CLI::App* slam = command(*app, "slam");
    // --resume is a flag without a value: the argument after it stays
    CHECK(hc::tools::typed_command_line(slam) == "harris-cosim slam --sequences 01 --no-vo-level --out 'a b'");
    const std::string s = hc::tools::effective_settings(slam);
    CHECK(s.find("sequences=01\n") != std::string::npos);
    CHECK(s.find("no-vo-level=true\n") != std::string::npos);     // given
    CHECK(s.find("vo-two-view=false\n") != std::string::npos);    // not given
    CHECK(s.find("no-vo-offset-uncertainty=false\n") != std::string::npos);   // not given
    CHECK(s.find("vo-max-range=60\n") != std::string::npos);      // its default
    CHECK(s.find("out=a b\n") != std::string::npos);
    CHECK(s.find("jobs=") == std::string::npos);                  // sharding flags are not settings
    CHECK(s.find("resume=") == std::string::npos);
    CHECK(s.find("help=") == std::string::npos);
}
