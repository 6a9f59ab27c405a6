// squares_job.hpp: the "squares" job kind of the runner tests (see cluster_test_worker.cpp).
#pragma once

#include <unistd.h>

#include "io/cluster/cluster.hpp"

namespace hc::cluster::test {

/// A fresh (removed, not created) scratch path <tmp>/hc-cluster-test-<pid>/<name>.
inline fs::path scratch(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("hc-cluster-test-" + std::to_string(::getpid())) / name;
    fs::remove_all(d);
    return d;
}

inline JobRegistry squares_registry() {
    JobRegistry reg;
    reg.add({"squares",
             [](const json&, const json& shard, std::size_t) {
                 long sum = 0;
                 json items = json::array();
                 for (long i = shard.at("first").get<long>(); i < shard.at("last").get<long>(); ++i) {
                     sum += i * i;
                     items.push_back(i);
                 }
                 return json{{"sum", sum}, {"items", items}};
             },
             [](const json&, const std::vector<json>& data) {
                 long sum = 0;
                 json items = json::array();
                 for (const auto& d : data) {
                     sum += d.at("sum").get<long>();
                     for (const auto& i : d.at("items")) items.push_back(i);
                 }
                 return json{{"sum", sum}, {"items", items}};
             }});
    return reg;
}

/// A manifest of `k` shards over [0, n).
inline Manifest squares_manifest(long n, int k) {
    Manifest m;
    m.job = "squares";
    m.common = {{"n", n}};
    for (auto [a, b] : split_range(0, n, k)) m.shards.push_back({{"first", a}, {"last", b}});
    return m;
}

}  // namespace hc::cluster::test
