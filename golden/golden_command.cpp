// golden_command.cpp: `harris-cosim golden` (golden.hpp: run_golden_command).
#include <cstdio>

#include "golden/golden.hpp"
#include "model/util/errors.hpp"

namespace fs = std::filesystem;

namespace hc::golden {

void run_golden_command(const fs::path& dir, const std::string& set_file, bool check) {
    const auto set = util::read_regression_set(set_file.empty() ? dir / "regression-set.txt" : fs::path(set_file));
    const auto files = golden_files(set, dir);
    int bad = 0;
    for (const auto& f : files) {
        if (!check) {
            util::write_file_atomic(f.path, f.text);
            continue;
        }
        const std::string msg = compare_golden(f);
        if (!msg.empty()) {
            std::fprintf(stderr, "golden mismatch: %s\n", msg.c_str());
            ++bad;
        }
    }
    if (check)
        std::printf("harris-cosim golden: %zu files checked, %s\n", files.size(),
                    bad ? (std::to_string(bad) + " differ").c_str() : "all equal");
    else
        std::printf("harris-cosim golden: %zu files written to %s\n", files.size(), dir.c_str());
    if (bad) throw MismatchError(std::to_string(bad) + " golden file(s) differ from the cycle model");
}

}  // namespace hc::golden
