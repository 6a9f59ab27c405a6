// cmd_golden.cpp: `harris-cosim golden`: regenerates the committed reference results in
// golden/ from the cycle model, or checks the model against them (--check). The files are
// described in golden/golden.hpp.
#include <cstdio>
#include <filesystem>

#include "golden/golden.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

void add_golden_command(CLI::App& app) {
    struct Opts {
        std::string out = "golden";
        std::string set;
        bool check = false;
    };
    const auto [cmd, o] = add_command<Opts>(app, "golden",
        "Regenerate the golden reference results from the cycle model (a deliberate act: review the diff),\n"
        "or with --check compare the model with the committed files (exit status 1 on any difference).");
    cmd->add_option("--out", o->out, "golden directory")->capture_default_str();
    cmd->add_option("--set", o->set, "regression-set file (default <out>/regression-set.txt)");
    cmd->add_flag("--check", o->check, "compare instead of writing; exit 1 on any difference");
    cmd->callback([o]() {
        const fs::path dir = o->out;
        const auto set = util::read_regression_set(o->set.empty() ? dir / "regression-set.txt" : fs::path(o->set));
        const auto files = regress::golden_files(set, dir);
        int bad = 0;
        for (const auto& f : files) {
            if (!o->check) {
                util::write_file_atomic(f.path, f.text);
                continue;
            }
            const std::string msg = regress::compare_golden(f);
            if (!msg.empty()) {
                std::fprintf(stderr, "golden mismatch: %s\n", msg.c_str());
                ++bad;
            }
        }
        if (o->check)
            std::printf("harris-cosim golden: %zu files checked, %s\n", files.size(),
                        bad ? (std::to_string(bad) + " differ").c_str() : "all equal");
        else
            std::printf("harris-cosim golden: %zu files written to %s\n", files.size(), dir.c_str());
        if (bad) throw MismatchError(std::to_string(bad) + " golden file(s) differ from the cycle model");
    });
}

}  // namespace hc::tools
