// frames.hpp: the frames a run streams through the design: image files, a KITTI-layout
// sequence or a synthetic pattern, loaded with errors that name the input.
//
// Errors: hc::InputError (model/util/errors.hpp) naming the file, directory or value.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "model/image/image.hpp"
#include "model/util/util.hpp"

namespace cv {
class Mat;
}

namespace hc::frames {

/// An 8-bit OpenCV image as a grey Image (colour converted as cv::COLOR_BGR2GRAY or
/// COLOR_BGRA2GRAY does); the caller has checked its depth.
Image image_of(const cv::Mat& m);

/// The image files of a folder (.png, .pgm, .ppm, .pbm, .jpg, .jpeg, .bmp, .tif, .tiff, .webp,
/// any case), sorted by name; none when `dir` is not a folder.
std::vector<std::filesystem::path> image_files_in(const std::filesystem::path& dir);

/// Reads an 8-bit image (grey, or colour converted to grey). Throws InputError naming the
/// file when it is missing, unreadable or not 8-bit.
Image load_image(const std::filesystem::path& p);

/// A centred crop of `width` x `height` (0 = keep). Throws InputError if larger than img.
Image crop(const Image& img, int width, int height, const std::string& what);

/// The data directory: `flag_value` (--data), else $HARRIS_COSIM_DATA, else ../shared/data
/// next to the source tree (HC_DEFAULT_DATA_DIR at build time). Empty if none exists.
std::optional<std::filesystem::path> data_dir(const std::string& flag_value);

/// The KITTI odometry root (the folder holding sequences/) a command reads: `kitti_flag`
/// (--kitti) when given, else data_dir(data_flag)/kitti when that is a directory; empty when
/// neither (the one rule of every command).
std::filesystem::path kitti_root(const std::string& kitti_flag, const std::string& data_flag);
/// kitti_root, or InputError "`needs`: give --kitti DIR ... or --data DIR ..." when empty.
std::filesystem::path require_kitti_root(const std::string& kitti_flag, const std::string& data_flag,
                                         const std::string& needs);

// The KITTI odometry layout, known here only (every command and library that reads KITTI asks
// these functions): a KITTI root holds sequences/NN/ (image_0/ the left images, image_1/ the
// right ones, calib.txt the rectified projections) and poses/NN.txt (the ground-truth poses).

/// <kitti_root>/sequences, the folder of the sequences.
std::filesystem::path kitti_sequences_dir(const std::filesystem::path& kitti_root);
/// <kitti_root>/sequences/NN.
std::filesystem::path kitti_sequence_dir(const std::filesystem::path& kitti_root, const std::string& sequence);
/// True when sequence NN has both image folders (image_0/ and image_1/).
bool is_kitti_sequence(const std::filesystem::path& kitti_root, const std::string& sequence);
/// InputError (naming the flag --sequences) listing every sequence of `seqs` that is not a
/// KITTI sequence under kitti_root/sequences/.
void check_kitti_sequences(const std::filesystem::path& kitti_root, const std::vector<std::string>& seqs);
/// `00-21` (a range, both ends included) or `00,01,05` (a list), each two digits or more
/// as KITTI names them. InputError naming the flag value (--sequences) otherwise.
std::vector<std::string> parse_sequences(const std::string& s);
/// <kitti_root>/poses/NN.txt, the ground-truth poses of sequence NN.
std::filesystem::path kitti_poses_file(const std::filesystem::path& kitti_root, const std::string& sequence);

/// A KITTI odometry sequence: sequences/NN/image_0 (left) and image_1 (right).
struct KittiSequence {
    std::filesystem::path root;   ///< .../sequences/NN
    std::vector<std::filesystem::path> left, right;   ///< sorted; right may be shorter
    int pairs() const { return static_cast<int>(std::min(left.size(), right.size())); }
    /// The sequence's calib.txt (rectified projections P0, P1, ...).
    std::filesystem::path calib_txt() const { return root / "calib.txt"; }
};
/// Throws InputError when the directory is not a KITTI sequence.
KittiSequence open_kitti(const std::filesystem::path& kitti_dir, const std::string& sequence);

/// The thesis's evaluation stream L0 R0 L1 R1 ... for stereo pairs [r.first, r.last).
/// Throws InputError naming `what` (e.g. "--pairs 50:60") and the last pair when the range
/// reaches past the sequence's stereo pairs; an open end (util::parse_range's) is clipped.
std::vector<std::filesystem::path> stereo_stream(const KittiSequence& s, util::Range r, const std::string& what,
                                                 int open_end = 1 << 30);

/// The frames of one evaluation: a stream of stereo pairs (2 frames each).
struct Stream {
    std::vector<Image> frames;         ///< L R L R ...
    std::vector<std::string> names;    ///< e.g. "01/L000003"
    std::vector<int> pair_index;       ///< stereo pair number of each frame
    std::string description;
};
/// Loads the stereo pairs `r` of a KITTI sequence (images in parallel on `threads`, 0: all
/// cores). Throws InputError when fewer than `min_pairs` pairs result or frames differ in size.
Stream load_kitti_stream(const std::filesystem::path& kitti_dir, const std::string& sequence, util::Range r,
                         const std::string& what, int threads, int min_pairs = 1);

/// The frames of a stream loaded as a run reaches them: names, pair numbers and the size
/// (from frame 0) up front, each frame's pixels when first asked for, kept until released,
/// so a run over a long stream holds only the frames it is working on.
class FrameFeed {
public:
    /// `load(k)` gives frame k (0 <= k < names.size()); it may throw InputError naming the file.
    FrameFeed(std::vector<std::string> names, std::vector<int> pair_index, std::string description,
              std::function<Image(int)> load);
    /// The frames of an in-memory stream (referenced, not copied: `s` must outlive the feed).
    static FrameFeed of(const Stream& s);

    int size() const { return static_cast<int>(names_.size()); }
    int width() const { return width_; }
    int height() const { return height_; }
    const std::vector<std::string>& names() const { return names_; }
    const std::vector<int>& pair_index() const { return pair_index_; }
    const std::string& description() const { return description_; }
    void describe(std::string d) { description_ = std::move(d); }

    /// Frame k, loaded now unless held or being loaded (then waited for; thread-safe; each
    /// frame is loaded once however many threads ask). InputError when it differs in size
    /// from frame 0 (or the load's own, naming the file); std::out_of_range outside the stream.
    std::shared_ptr<const Image> frame(int k);
    /// Starts loading frame k on a thread of its own, unless it is held, being loaded or
    /// outside the stream, so that a later frame(k) finds it ready; a failed load is
    /// reported by that frame(k). Loads started and not finished are waited for when the
    /// feed is destroyed.
    void prefetch(int k);
    /// Drops the frames below k from the feed (those still in use stay alive with their users).
    void release_below(int k);
    /// Frames loaded so far (a frame dropped and asked for again counts twice).
    long loads() const;

private:
    using Loaded = std::shared_future<std::shared_ptr<const Image>>;
    /// What the feed and its loading threads share (so the feed may be moved while one runs).
    struct State {
        std::function<Image(int)> load;
        std::vector<std::string> names;
        int width = 0, height = 0;
        std::mutex mu;
        std::map<int, Loaded> held;
        long loads = 0;
    };
    /// Frame k's pixels checked against frame 0's size.
    static std::shared_ptr<const Image> load_checked(State& st, int k);
    std::vector<std::string> names_;
    std::vector<int> pair_index_;
    std::string description_;
    int width_ = 0, height_ = 0;
    std::shared_ptr<State> state_;
    std::vector<std::future<void>> loading_;   ///< prefetches started (finished ones pruned)
};
/// How a feed is cut: its first `frames` frames (0: all; more than the stream holds is an
/// InputError naming --frames), each cropped around its centre to `width` x `height` (0: whole).
struct FeedCut {
    int frames = 0;
    int width = 0, height = 0;
};

/// Stereo pairs `r` of a KITTI sequence as a feed (the same checks, names and description as
/// load_kitti_stream, each image read when reached), cut by `cut`. InputError when the cut
/// stream spans fewer than `min_pairs` stereo pairs.
FrameFeed open_kitti_feed(const std::filesystem::path& kitti_dir, const std::string& sequence, util::Range r,
                          const std::string& what, int min_pairs = 1, const FeedCut& cut = {});

/// The stereo stream of a machine without KITTI data: pairs of consecutive frames of OpenCV's
/// sample video vtest.avi (opencv-doc) when installed, grey, centred 640x360 crop (the thesis's
/// camera size), 12 pairs at most; else the synthetic `blocks` pattern, 640x360. Pairs `r` of
/// it (an open end: all), cut to its first cut.frames frames.
FrameFeed default_stereo_feed(util::Range r, int frames = 0);

/// Which frames a command streams (the command line's frame-source flags, the same on every
/// command that reads a stream of images).
struct FrameSource {
    /// image files, glob patterns ('left*.png') and folders (their image files, sorted by
    /// name), streamed in order; or one video file (.avi, .mp4, ...), its frames in order
    std::vector<std::string> images;
    std::string pattern;               ///< synthetic pattern name
    std::string size;                  ///< WxH: pattern size, or centred crop of images
    int frames = 0;                    ///< number of frames (patterns; else the first N frames of the stream)
    std::string kitti;                 ///< KITTI odometry root (holding sequences/)
    std::string sequence = "01";
    std::string pairs;                 ///< a:b stereo pairs of the KITTI sequence
    std::string data;                  ///< data directory (else $HARRIS_COSIM_DATA, ../shared/data)
    std::uint32_t seed = 1;
};

struct LoadedFrames {
    std::vector<Image> frames;
    std::vector<std::string> names;
    std::string description;
};

/// How errors name the stereo pairs `o` picks: "--pairs a:b", or "--pairs (all)" without the flag.
std::string pairs_flag(const FrameSource& o);
/// The stereo pairs `o` picks: its --pairs range, or every pair (an open end) without the flag.
util::Range pair_range(const FrameSource& o);
/// pair_range for a job that splits whole stereo pairs into parts (KITTI --sequences, sharded
/// runs): --frames N, a count of one stream's frames, is refused there (InputError).
util::Range job_pair_range(const FrameSource& o);

/// True when `p` names a video file by its extension (.avi, .mp4, .mkv, .mov, ...).
bool is_video_file(const std::filesystem::path& p);

/// Image files, glob patterns and folders (their image files, sorted by name) as one list of
/// files, in the order given. InputError naming `what` for a missing file, a pattern that
/// matches nothing, a folder without images, or no item at all.
std::vector<std::filesystem::path> expand_image_list(const std::vector<std::string>& items, const std::string& what);

/// A user's stereo rig as the command line names it, with the same flags on every command that
/// reads one (--calib, --left, --right): the calibration `harris-cosim calibrate` wrote (or a
/// KITTI-style calib.txt of rectified images) and the left and right images, paired in order.
struct RigSource {
    std::string calib;                      ///< the calibration file ("": no rig)
    std::vector<std::string> left, right;   ///< image files, glob patterns or folders
    /// True when any of the three flags is given.
    bool given() const { return !calib.empty() || !left.empty() || !right.empty(); }
};
/// A rig's stereo pairs: its calibration file and left[i], right[i] for each pair i.
struct RigPairs {
    std::filesystem::path calib;
    std::vector<std::filesystem::path> left, right;
    int pairs() const { return static_cast<int>(left.size()); }
};
/// The pairs `r` names (expand_image_list on --left and --right). InputError naming the flags
/// for images without --calib, --calib without both lists of images, lists that differ in
/// length (both counts named), and expand_image_list's own.
RigPairs open_rig(const RigSource& r);

/// What a command streams when no frame-source flag names a source: `pattern`, three 64x36
/// frames of the `blocks` pattern (a --pattern's defaults); `stereo`, the KITTI sequence
/// `--sequence` of the data directory when it has a KITTI root (a missing sequence is an
/// InputError naming it), else default_stereo_feed.
enum class WhenNone { pattern, stereo };

/// The frames `o` names as a feed, each read (cropped, converted to grey) when the run
/// reaches it: image files, globs, folders, a video, a KITTI sequence's stereo stream or a
/// synthetic pattern; with none of them, what `none` says. Frames of images, a video or a
/// pattern pair up in order (0 1, 2 3, ...) as a KITTI stream's L R do. `--frames N` takes
/// the first N frames of any of them; `--pairs a:b` picks the stereo pairs of a KITTI or the
/// default stereo stream. A KITTI stream spanning fewer than `min_pairs` pairs is refused.
/// InputError naming the input (as load_frames).
FrameFeed open_feed(const FrameSource& o, WhenNone none = WhenNone::pattern, int min_pairs = 1);

/// Loads the frames; throws InputError naming the bad input (including a stream the design
/// cannot be built for). With nothing chosen, three 64x36 frames of the `blocks` pattern.
LoadedFrames load_frames(const FrameSource& o);

/// Pointers to the frames, in order (what HostDriver takes).
std::vector<const Image*> pointers(const std::vector<Image>& frames);

}  // namespace hc::frames
