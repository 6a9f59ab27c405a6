// util.hpp: the small helpers every library shares, one copy each: running a child
// process, a content hash, reading and atomically writing files, and the parsers of the
// little text formats the command line and the data files use.
//
// Errors: functions that read user input throw hc::InputError (model/util/errors.hpp) naming it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/util/errors.hpp"

namespace hc::util {

// ---- child processes ----------------------------------------------------------------

struct ProcessOptions {
    std::vector<std::string> extra_env{};   ///< "NAME=value", added to (or overriding) the environment
    std::filesystem::path cwd{};          ///< working directory (empty: the current one)
    std::filesystem::path log{};          ///< stdout and stderr appended here (empty: inherited)
    std::filesystem::path stdout_file{};  ///< stdout alone to this file, truncated (with log: stderr to log)
};

/// Runs argv (argv[0] a path, or a name looked up in $PATH) and waits for it. Returns the
/// exit status, 128 + the signal number when it was killed. Throws SimulatorError when the
/// program cannot be started.
int run_process(const std::vector<std::string>& argv, const ProcessOptions& opt = {});

/// The last `n` characters of a log file ("(no log)" when it cannot be read).
std::string log_tail(const std::filesystem::path& p, std::size_t n = 2000);

// ---- hashing --------------------------------------------------------------------------

/// FNV-1a, 64 bits: a content hash for cache keys (not a security boundary). Chain calls
/// by passing the previous hash as `h`.
std::uint64_t fnv1a(std::string_view s, std::uint64_t h = 14695981039346656037ULL);
/// 16 lower-case hex digits.
std::string hex64(std::uint64_t h);

/// A command line as the user typed it, for a report: `program` then each argument, quoted
/// for a POSIX shell where it holds anything but letters, digits and -_./:=,+@% (so pasting
/// it into a shell runs the same command).
std::string shell_command_line(const std::string& program, const std::vector<std::string>& args);

// ---- files ----------------------------------------------------------------------------

/// The bytes of a file. Throws InputError "cannot read '<what>'" (what defaults to the path).
std::string read_file(const std::filesystem::path& p, const std::string& what = "");

/// Writes `bytes` to `target` atomically: a temporary beside it, then a rename, so that an
/// interrupted run never leaves half a file and never destroys an existing one early.
/// Creates the parent directory. Throws InputError naming the target when it cannot be written
/// (also when its folder cannot be made, e.g. a component of the path is a file); no temporary
/// is left behind.
void write_file_atomic(const std::filesystem::path& target, const std::string& bytes);

/// A scratch directory under the system's temporary directory, removed on destruction.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& prefix = "harris-cosim");
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// ---- little text formats --------------------------------------------------------------

/// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_csv(const std::string& s, char sep = ',');

/// A half-open range "a:b" (0 <= a < b; b excluded). An empty side means 0 or `open_end`
/// ("3:" is 3..open_end). `what` names the input in the InputError (e.g. "--pairs").
struct Range {
    int first = 0, last = 0;
};
Range parse_range(const std::string& s, const std::string& what, int open_end = 1 << 30);

/// "WxH" -> (W, H), both positive. Throws InputError naming `what`.
std::pair<int, int> parse_size(const std::string& s, const std::string& what = "--size");

/// One stream of the regression set (golden/regression-set.txt), one a line:
/// `pattern WxH frames idle_every`; '#' starts a comment line. A stimulus image instead of a
/// pattern: `FILE.pgm WxH frames idle_every [breaks=CONFIG.json]`, the image chained `frames`
/// times; `breaks` names the formats (a --config file) the image is a witness against
/// (it wraps a register of that configuration). Both paths are relative to the set's file.
struct RegressionStream {
    std::string pattern;               ///< a pattern name, or the image's path as written
    int width = 0;
    int height = 0;
    int frames = 0;
    int idle_every = 0;
    std::filesystem::path image;       ///< the image (resolved), empty for a pattern
    std::filesystem::path breaks;      ///< the formats file it is a witness against (resolved), or empty
    /// "random_40x30" (an image: its file stem, "sobel_w-10_sobel_x_16x12"): the stem of the stream's golden files.
    std::string stem() const;
    /// "40x30"
    std::string size() const;
};
/// Throws InputError naming the file and line when it cannot be read or a line is bad.
std::vector<RegressionStream> read_regression_set(const std::filesystem::path& p);

// ---- plots ----------------------------------------------------------------------------

/// A plot axis framed on its data: [lo, hi] spans the finite values of `v` with `margin` of
/// their extent on either side (at least `min_span` wide, centred on them), clipped to
/// [floor, ceil] (a recall axis: 0 and 1). With no finite value: [floor, ceil] when both are
/// finite, else [0, 1].
struct AxisRange {
    double lo = 0, hi = 1;
    /// "[lo:hi]" for gnuplot's `set xrange` / `set yrange`
    std::string gnuplot() const;
};
AxisRange axis_range(const std::vector<double>& v, double margin = 0.05, double floor = -1e300,
                     double ceil = 1e300, double min_span = 1e-6);

}  // namespace hc::util
