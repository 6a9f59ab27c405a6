// fuzz_main.cpp: the seeded mutation driver of the fuzz targets (fuzz_targets.hpp), for
// compilers without libFuzzer (g++). Usage:
//
//   hc-fuzz --target NAME [--runs N] [--max-seconds S] [--seed K] [--timeout S] [--work DIR]
//   hc-fuzz --list
//
// Each seed runs once as is; then, until N runs or S seconds, an input is a seed (or an
// earlier accepted input) with 1..6 random edits: bit flips, random bytes, insertions and
// deletions of runs, duplicated runs, dictionary tokens of the format, truncation, splices
// of two seeds. The same --seed gives the same inputs. The contract of fuzz_targets.hpp is
// checked on every input; a broken one, a crash (signal) or a hang (an input that takes
// longer than --timeout seconds) saves the input to DIR/defect-<target>-<hash> and exits 1.
// Exit 0 with a summary line: inputs run, accepted, rejected as input errors, seconds.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "tests/fuzz/fuzz_targets.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;
using hc::fuzz::Target;

namespace {

// What a signal handler needs to save the input being run (async-signal-safe writes only).
const std::string* g_input = nullptr;
char g_defect_path[4096] = {0};
const char* g_what = "crash";

void save_and_exit(int sig) {
    const int fd = open(g_defect_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0 && g_input) {
        ssize_t n = write(fd, g_input->data(), g_input->size());
        (void)n;
        close(fd);
    }
    const char* kind = sig == SIGALRM ? "hang (input ran longer than --timeout)" : g_what;
    ssize_t n = write(2, "hc-fuzz: ", 9);
    n = write(2, kind, std::strlen(kind));
    n = write(2, "; input saved to ", 17);
    n = write(2, g_defect_path, std::strlen(g_defect_path));
    n = write(2, "\n", 1);
    (void)n;
    _exit(1);
}

std::string mutate(const std::string& base, const Target& t, const std::vector<std::string>& pool, std::mt19937_64& rng) {
    std::string s = base;
    auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int e = 0; e < edits; ++e) {
        switch (rng() % 9) {
            case 0:   // flip a bit
                if (!s.empty()) s[pick(s.size())] ^= static_cast<char>(1u << (rng() % 8));
                break;
            case 1:   // a random byte
                if (!s.empty()) s[pick(s.size())] = static_cast<char>(rng());
                break;
            case 2: {   // insert random bytes
                std::string ins(1 + pick(8), '\0');
                for (char& c : ins) c = static_cast<char>(rng());
                s.insert(pick(s.size() + 1), ins);
                break;
            }
            case 3:   // delete a run
                if (!s.empty()) {
                    const std::size_t at = pick(s.size());
                    s.erase(at, 1 + pick(std::min<std::size_t>(32, s.size() - at)));
                }
                break;
            case 4:   // duplicate a run
                if (!s.empty()) {
                    const std::size_t at = pick(s.size());
                    const std::string run = s.substr(at, 1 + pick(16));
                    s.insert(pick(s.size() + 1), run);
                }
                break;
            case 5:   // insert a token of the format
            case 6:
                if (!t.tokens.empty()) s.insert(pick(s.size() + 1), t.tokens[pick(t.tokens.size())]);
                break;
            case 7:   // truncate
                if (!s.empty()) s.resize(pick(s.size()));
                break;
            case 8: {   // splice: our head, another input's tail
                const std::string& other = pool[pick(pool.size())];
                s = s.substr(0, pick(s.size() + 1)) + other.substr(pick(other.size() + 1));
                break;
            }
        }
    }
    if (s.size() > (1u << 16)) s.resize(1u << 16);
    return s;
}

int usage(const char* msg) {
    std::fprintf(stderr, "hc-fuzz: %s\nusage: hc-fuzz --target NAME [--runs N] [--max-seconds S] [--seed K] "
                         "[--timeout S] [--work DIR] | --list\n", msg);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string name, work;
    long runs = 10000;
    double max_seconds = 0;
    unsigned long long seed = 1;
    unsigned timeout = 10;
    bool list = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw hc::InputError(a + " needs a value");
            return argv[++i];
        };
        try {
            if (a == "--target") name = value();
            else if (a == "--runs") runs = std::stol(value());
            else if (a == "--max-seconds") max_seconds = std::stod(value());
            else if (a == "--seed") seed = std::stoull(value());
            else if (a == "--timeout") timeout = static_cast<unsigned>(std::stoul(value()));
            else if (a == "--work") work = value();
            else if (a == "--list") list = true;
            else return usage(("unknown flag " + a).c_str());
        } catch (const std::exception& e) {
            return usage(e.what());
        }
    }
    const auto all = hc::fuzz::targets(HC_SOURCE_DIR);
    if (list) {
        for (const auto& t : all) std::printf("%-16s %s\n", t.name.c_str(), t.reads.c_str());
        return 0;
    }
    const Target* t = nullptr;
    for (const auto& c : all)
        if (c.name == name) t = &c;
    if (!t) return usage(("unknown target '" + name + "' (--list names them)").c_str());
    const fs::path dir = work.empty() ? fs::temp_directory_path() / ("hc-fuzz-" + std::to_string(getpid())) : fs::path(work);
    fs::create_directories(dir / "input");
    const fs::path file = dir / "input" / t->file_name;

    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL, SIGALRM}) std::signal(sig, save_and_exit);
    std::mt19937_64 rng(seed);
    std::vector<std::string> pool = t->seeds;   // seeds, then accepted inputs (bounded)
    const auto t0 = std::chrono::steady_clock::now();
    long n = 0, accepted = 0, rejected = 0;
    std::string input;
    g_input = &input;
    for (; n < runs + static_cast<long>(t->seeds.size()); ++n) {
        if (max_seconds > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > max_seconds)
            break;
        input = n < static_cast<long>(t->seeds.size()) ? t->seeds[static_cast<std::size_t>(n)]
                                                       : mutate(pool[rng() % pool.size()], *t, pool, rng);
        const std::string hash = hc::util::hex64(hc::util::fnv1a(input));
        std::snprintf(g_defect_path, sizeof g_defect_path, "%s", (dir / ("defect-" + t->name + "-" + hash)).c_str());
        alarm(timeout);
        try {
            if (hc::fuzz::run_one(*t, input, file)) {
                ++accepted;
                if (pool.size() < 256) pool.push_back(input);
            } else {
                ++rejected;
            }
        } catch (const hc::fuzz::FuzzDefect& e) {
            alarm(0);
            std::ofstream(g_defect_path, std::ios::binary) << input;
            std::fprintf(stderr, "hc-fuzz: DEFECT after %ld inputs: %s\nhc-fuzz: input saved to %s\n", n, e.what(),
                         g_defect_path);
            return 1;
        }
        alarm(0);
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("hc-fuzz %s: %ld inputs (%zu seeds), %ld accepted, %ld rejected as input errors, 0 defects, %.1f s\n",
                t->name.c_str(), n, t->seeds.size(), accepted, rejected, secs);
    if (work.empty()) fs::remove_all(dir);
    else fs::remove_all(dir / "input");
    return 0;
}
