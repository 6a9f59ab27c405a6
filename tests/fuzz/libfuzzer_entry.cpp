// libfuzzer_entry.cpp: the fuzz targets (fuzz_targets.hpp) under libFuzzer, for clang
// builds (-fsanitize=fuzzer). The target is chosen by $HC_FUZZ_TARGET; a broken contract
// aborts, which libFuzzer reports with the input saved as crash-<sha1>.
//
//   HC_FUZZ_TARGET=formats-json hc-libfuzzer -max_total_time=60 corpus/
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

#include "tests/fuzz/fuzz_targets.hpp"

namespace {
const hc::fuzz::Target* g_target = nullptr;
std::filesystem::path g_file;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    static const auto all = hc::fuzz::targets(HC_SOURCE_DIR);
    const char* name = std::getenv("HC_FUZZ_TARGET");
    for (const auto& t : all)
        if (name && t.name == name) g_target = &t;
    if (!g_target) {
        std::fprintf(stderr, "hc-libfuzzer: set HC_FUZZ_TARGET to one of:");
        for (const auto& t : all) std::fprintf(stderr, " %s", t.name.c_str());
        std::fprintf(stderr, "\n");
        std::exit(2);
    }
    const auto dir = std::filesystem::temp_directory_path() / ("hc-libfuzzer-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    g_file = dir / g_target->file_name;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
    try {
        (void)hc::fuzz::run_one(*g_target, std::string(reinterpret_cast<const char*>(data), size), g_file);
    } catch (const hc::fuzz::FuzzDefect& e) {
        std::fprintf(stderr, "hc-libfuzzer: DEFECT: %s\n", e.what());
        std::abort();
    }
    return 0;
}
