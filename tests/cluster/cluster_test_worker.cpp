// cluster_test_worker: a worker for the runner tests. Its one job kind, "squares", sums i^2
// over each shard's [first, last) and lists the i; the merge adds the sums and joins the
// lists in shard order. It takes DIR INDEX, or `shard run DIR INDEX` as a JobRunner starts
// its workers. Two environment variables make a shard misbehave on purpose:
//   HC_TEST_SLEEP_INDEX=k  shard k sleeps 60 s before computing (to be killed mid-run);
//   HC_TEST_FAIL_INDEX=k   shard k exits 1 without a result.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "io/cluster/cluster.hpp"
#include "tests/cluster/squares_job.hpp"

int main(int argc, char** argv) {
    // `shard run DIR INDEX` as a JobRunner starts its workers (io/cluster/runner.hpp)
    if (argc == 5 && std::string(argv[1]) == "shard" && std::string(argv[2]) == "run") argv += 2, argc -= 2;
    if (argc != 3) {
        std::fprintf(stderr, "usage: cluster_test_worker [shard run] DIR INDEX\n");
        return 2;
    }
    const std::size_t index = std::stoul(argv[2]);
    auto env_index = [](const char* name) {
        const char* v = std::getenv(name);
        return v ? std::stol(v) : -1L;
    };
    if (env_index("HC_TEST_FAIL_INDEX") == static_cast<long>(index)) return 1;
    if (env_index("HC_TEST_SLEEP_INDEX") == static_cast<long>(index))
        std::this_thread::sleep_for(std::chrono::seconds(60));
    try {
        hc::cluster::run_shard(hc::cluster::test::squares_registry(), argv[1], index,
                               {{"cluster_test_worker", "1"}});
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cluster_test_worker: %s\n", e.what());
        return 3;
    }
    return 0;
}
