// files.cpp: reading, atomic writing, scratch directories (util.hpp).
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::util {

std::string read_file(const fs::path& p, const std::string& what) {
    std::ifstream f(p, std::ios::binary);
    if (!f || fs::is_directory(p)) throw InputError("cannot read " + (what.empty() ? "'" + p.string() + "'" : what));
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void write_file_atomic(const fs::path& target, const std::string& bytes) {
    if (fs::is_directory(target)) throw InputError("output '" + target.string() + "' is a directory");
    if (target.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(target.parent_path(), ec);
        if (ec || !fs::is_directory(target.parent_path()))
            throw InputError("cannot write '" + target.string() + "': cannot make its folder '" + target.parent_path().string() +
                             "'" + (ec ? " (" + ec.message() + ")" : ""));
    }
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
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + target.string() + "': cannot rename its temporary into place");
    }
}

ScratchDir::ScratchDir(const std::string& prefix) {
    std::string tmpl = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (!::mkdtemp(tmpl.data())) throw InternalError("cannot create a scratch directory in " + fs::temp_directory_path().string());
    path_ = tmpl;
}

ScratchDir::~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

}  // namespace hc::util
