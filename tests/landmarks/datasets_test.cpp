// datasets_test.cpp: the dataset a choice of flags names (open_dataset), refused without data.
#include <catch2/catch.hpp>

#include <filesystem>

#include "mapping/landmarks/landmarks.hpp"

using namespace hc::landmarks;

TEST_CASE("a rig's calibration without its images, images without a rig and an unknown dataset are input errors",
          "[landmarks][datasets]") {
    std::filesystem::path root;
    DatasetChoice c;
    c.rig.calib = "rig.yml";
    c.rig.left = {"left.png"};
    CHECK_THROWS_WITH(open_dataset(c, root), Catch::Contains("--calib needs the rig's images: --left and --right"));
    c.rig.calib.clear();
    CHECK_THROWS_WITH(open_dataset(c, root), Catch::Contains("--left and --right are the images of a rig"));
    c.rig.left.clear();
    c.dataset = "tum";
    CHECK_THROWS_AS(open_dataset(c, root), hc::InputError);
    CHECK_THROWS_WITH(open_dataset(c, root), Catch::Contains("--dataset 'tum' (middlebury or kitti)"));
    CHECK(root.empty());
}
