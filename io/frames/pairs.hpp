// pairs.hpp: a range of stereo pairs checked against the pairs there are, the one rule of every
// command's --pairs (frames::stereo_stream on a KITTI sequence, slam on a rig's lists).
#pragma once

#include <string>

#include "model/util/util.hpp"

namespace hc::frames {

/// The pairs [r.first, r.last) of `n` stereo pairs, an open end (util::parse_range's) clipped
/// to n. Throws InputError naming `what` (e.g. "--pairs 50:60"), `of` (e.g. "KITTI sequence
/// '...'") and the last pair when the range reaches or starts past them.
util::Range pairs_within(util::Range r, int n, const std::string& what, const std::string& of, int open_end = 1 << 30);

}  // namespace hc::frames
