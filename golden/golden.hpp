// golden.hpp: the golden reference files of the synthetic regression set (golden/), made
// by the cycle model; `harris-cosim golden` regenerates or checks them.
//
// Files (each headed by the command that made it):
//   reads_<pattern>_<WxH>.csv   every read of a regression stream: write,frame,x,y,value
//   maxima_<pattern>_<WxH>.csv  every change of find-max's published maximum: write,max
//   stages_<pattern>_<WxH>.txt  for tiny frames: every observed register after every write
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "model/image/image.hpp"
#include "model/util/util.hpp"

namespace hc::golden {

/// One golden file: where it goes and what it holds.
struct GoldenFile {
    std::filesystem::path path;
    std::string text;
};

/// The frames of a regression stream: its pattern's frames 0..frames-1 (seed 1), or its
/// image chained `frames` times. InputError naming the file when an image is unreadable or
/// not the stream's size.
std::vector<Image> stream_frames(const util::RegressionStream& s);

/// Every golden file for the streams of `set` (reads and maxima) and the tiny streams
/// (stages), under `dir`, made by the cycle model with the thesis's formats.
std::vector<GoldenFile> golden_files(const std::vector<util::RegressionStream>& set, const std::filesystem::path& dir);

/// "" when the committed file equals `now`, else the first differing line, named.
/// Throws InputError when the committed file is missing.
std::string compare_golden(const GoldenFile& now);

/// `harris-cosim golden`: writes every golden file of the regression set `set` (default
/// <dir>/regression-set.txt) into `dir`, or with `check` compares each with the committed one
/// (each difference on stderr). Prints a summary line; MismatchError when a file differs.
void run_golden_command(const std::filesystem::path& dir, const std::string& set, bool check);

}  // namespace hc::golden
