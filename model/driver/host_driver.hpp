// host_driver.hpp: model of the thesis's host driver (appendix C, hwHarris::apply): the
// order in which the ARM writes pixels to the co-processor and reads corner bits back.
//
// For a frame of `rows` x `cols` pixels, with di = rows/2-3 and dj = cols/2-3:
//  - window rows i = 3 .. rows/2-1, window columns j = 0 .. cols/2+2;
//  - each column is 7 writes (k = -3..3), each word packing four pixels:
//      byte 0 (i+k, j)   byte 1 (i+k+di, j)   byte 2 (i+k, j+dj)   byte 3 (i+k+di, j+dj);
//  - after a column's 7th write the host reads the corner bits of the window centred at
//    (x, y) = (j-5, i), the column two before (it tracks (x, y) over the last 3 columns,
//    across rows), when x >= 3: bit 3 -> (x, y), bit 2 -> (x, y+di), bit 1 -> (x+dj, y),
//    bit 0 -> (x+dj, y+di);
//  - frames are chained: after a frame's last column the host writes columns 0 and 1 of
//    the next frame's first window row, reading the last two windows of this frame after
//    each; every frame but the first then skips those two columns. The last frame of a
//    stream has no successor: its last two windows are never read.
// Odd sizes: only the first 2*(cols/2) columns and 2*(rows/2) rows are ever sent.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc {

/// Where a write's pixels come from.
struct WritePos {
    int frame = 0;      ///< frame index in the stream
    int i = 0;          ///< window row (centre row of quadrant 0)
    int j = 0;          ///< window column written (host loop index)
    int k = 0;          ///< row within the column, -3..3
    bool tail = false;  ///< a preload write of the next frame (frame is then the next one)
};

/// A read: the centre of quadrant 0's window whose bits come back, and the frame they
/// belong to.
struct ReadPos {
    int frame = 0;
    int x = 0;
    int y = 0;
};

struct Corner {
    int frame;
    int x;
    int y;
    friend bool operator==(const Corner&, const Corner&) = default;
    friend auto operator<=>(const Corner&, const Corner&) = default;
};

/// One bus write, and the read that follows it when the host reads.
struct BusEvent {
    std::uint32_t data = 0;
    WritePos pos;
    std::optional<ReadPos> read;
};

/// The driver's position in its stream (its loop variables): with the cycle model's state
/// (HarrisTop::save_state) it resumes a stream half-way.
struct DriverState {
    int frame = 0, i = 3, j = 0, k = -3;
    bool in_tail = false;
    int tail_col = 0;
    bool preload = true, done = false;
    int px[3] = {-1, -1, -1};
    int py[3] = {-1, -1, -1};
    bool column_open = false;
    friend bool operator==(const DriverState&, const DriverState&) = default;
};

class HostDriver {
public:
    /// `frames` must all have the geometry's size; they are referenced, not copied.
    HostDriver(const Geometry& g, std::vector<const Image*> frames);

    /// The next bus event of the stream; false at its end.
    bool next(BusEvent& ev);

    /// Writes in the whole stream, and reads.
    long total_writes() const;
    long total_reads() const;

    /// The image pixel of the window centre for quadrant q (0..3) of a read at (x, y).
    Corner quadrant_centre(const ReadPos& r, int q) const;
    /// Image positions of the corner bits a read returned (bit 3 = quadrant 0).
    void decode(const ReadPos& r, std::uint32_t value, std::vector<Corner>& out) const;
    /// The window centre of quadrant q for a write position's column (x = j - 3, y = i).
    Corner write_centre(const WritePos& p, int q) const;

    const Geometry& geometry() const { return g_; }

    /// Points frame k at `im` (the geometry's size; referenced, not copied): a stream whose
    /// frames are loaded as the driver reaches them sets each before its first write, and
    /// the frame after it before the preload at the frame's end.
    void set_frame(int k, const Image* im);

    /// Where the stream stands: the next call of next() continues from here.
    DriverState state() const;
    /// Continues from a state() of a driver over the same geometry and number of frames.
    void restore(const DriverState& s);

private:
    void start_column();
    Geometry g_;
    std::vector<const Image*> frames_;
    int di_, dj_;
    // loop state
    int frame_ = 0;
    int i_ = 3, j_ = 0, k_ = -3;
    bool in_tail_ = false;
    int tail_col_ = 0;
    bool preload_ = true;
    bool done_ = false;
    int px_[3] = {-1, -1, -1};
    int py_[3] = {-1, -1, -1};
    bool column_open_ = false;
};

/// A host driver over frames loaded as it reaches them: `frame(k)` is asked for frame k
/// once, before its first write (the driver's frame and the one after it are held, for the
/// preload at a frame's end; every other frame is a blank never sent), so a stream of any
/// length holds two frames.
class FeedDriver {
public:
    using FrameAt = std::function<std::shared_ptr<const Image>(int frame)>;
    /// A stream of `frames` frames of the geometry's size. std::invalid_argument as HostDriver.
    FeedDriver(const Geometry& g, int frames, FrameAt frame);
    /// Continues from a HostDriver::state() (as HostDriver::restore); call before next().
    void restore(const DriverState& s);
    /// The next bus event, loading the frame after the driver's when its body starts.
    bool next(BusEvent& ev);
    const HostDriver& driver() const { return drv_; }

private:
    void need(int k);
    FrameAt frame_;
    Image blank_;
    HostDriver drv_;
    int total_;
    int newest_ = -1, body_ = -1;
    bool started_ = false;
    std::vector<std::pair<int, std::shared_ptr<const Image>>> held_;
};

}  // namespace hc
