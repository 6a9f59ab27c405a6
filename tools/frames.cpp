#include "frames.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

namespace fs = std::filesystem;

namespace hc::tools {

Image load_image(const fs::path& p) {
    if (!fs::exists(p)) throw InputError("image '" + p.string() + "' does not exist");
    if (!fs::is_regular_file(p)) throw InputError("image '" + p.string() + "' is not a file");
    cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
    if (m.empty()) throw InputError("image '" + p.string() + "' cannot be decoded (corrupt or not an image)");
    if (m.depth() != CV_8U)
        throw InputError("image '" + p.string() + "' is not 8-bit (depth code " + std::to_string(m.depth()) +
                         "); the co-processor takes 8-bit grey pixels");
    if (m.channels() == 3) cv::cvtColor(m, m, cv::COLOR_BGR2GRAY);
    else if (m.channels() == 4) cv::cvtColor(m, m, cv::COLOR_BGRA2GRAY);
    else if (m.channels() != 1)
        throw InputError("image '" + p.string() + "' has " + std::to_string(m.channels()) + " channels");
    Image img(m.cols, m.rows);
    for (int r = 0; r < m.rows; ++r) std::copy_n(m.ptr<std::uint8_t>(r), m.cols, &img.at(r, 0));
    return img;
}

Image crop(const Image& img, int width, int height, const std::string& what) {
    const int w = width > 0 ? width : img.width;
    const int h = height > 0 ? height : img.height;
    if (w > img.width || h > img.height)
        throw InputError(what + " is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                         ", smaller than the requested " + std::to_string(w) + "x" + std::to_string(h));
    if (w == img.width && h == img.height) return img;
    const int x0 = (img.width - w) / 2, y0 = (img.height - h) / 2;
    Image out(w, h);
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) out.at(r, c) = img.at(y0 + r, x0 + c);
    return out;
}

std::optional<fs::path> data_dir(const std::string& flag_value) {
    if (!flag_value.empty()) {
        if (!fs::is_directory(flag_value)) throw InputError("data directory '" + flag_value + "' does not exist");
        return fs::path(flag_value);
    }
    if (const char* env = std::getenv("HARRIS_COSIM_DATA"); env && *env) {
        if (!fs::is_directory(env))
            throw InputError(std::string("HARRIS_COSIM_DATA='") + env + "' is not a directory");
        return fs::path(env);
    }
#ifdef HC_DEFAULT_DATA_DIR
    if (fs::is_directory(HC_DEFAULT_DATA_DIR)) return fs::path(HC_DEFAULT_DATA_DIR);
#endif
    return std::nullopt;
}

namespace {
std::vector<fs::path> sorted_images(const fs::path& dir) {
    std::vector<fs::path> v;
    if (!fs::is_directory(dir)) return v;
    for (const auto& e : fs::directory_iterator(dir)) {
        const auto ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".pgm")) v.push_back(e.path());
    }
    std::sort(v.begin(), v.end());
    return v;
}
}  // namespace

KittiSequence open_kitti(const fs::path& kitti_dir, const std::string& sequence) {
    KittiSequence s;
    s.root = kitti_dir / "sequences" / sequence;
    if (!fs::is_directory(s.root))
        throw InputError("KITTI sequence directory '" + s.root.string() + "' does not exist");
    s.left = sorted_images(s.root / "image_0");
    s.right = sorted_images(s.root / "image_1");
    if (s.left.empty()) throw InputError("'" + (s.root / "image_0").string() + "' holds no images");
    return s;
}

std::vector<fs::path> stereo_stream(const KittiSequence& s, int first, int last) {
    std::vector<fs::path> out;
    const int n = static_cast<int>(std::min(s.left.size(), s.right.size()));
    for (int k = std::max(0, first); k < std::min(last, n); ++k) {
        out.push_back(s.left[k]);
        out.push_back(s.right[k]);
    }
    return out;
}

void write_file_atomic(const fs::path& target, const std::string& bytes) {
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
    const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) throw InputError("cannot write '" + tmp.string() + "'");
        f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!f) {
            f.close();
            fs::remove(tmp);
            throw InputError("cannot write '" + tmp.string() + "'");
        }
    }
    fs::rename(tmp, target);
}

}  // namespace hc::tools
