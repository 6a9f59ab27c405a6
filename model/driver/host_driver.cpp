#include "model/driver/host_driver.hpp"

#include <stdexcept>
#include <string>

namespace hc {

HostDriver::HostDriver(const Geometry& g, std::vector<const Image*> frames)
    : g_(g), frames_(std::move(frames)), di_(g.di()), dj_(g.dj()) {
    g_.validate();
    if (frames_.empty()) throw std::invalid_argument("host driver: no frames to send");
    // Appendix C clears `preload` only on the second window row (i > 3). With a single window
    // row (height 8 or 9) it never does, so the thesis's host would re-send the two preloaded
    // columns of every chained frame and drift out of step with the design's frame counter.
    if (frames_.size() > 1 && g.rows() < 2)
        throw std::invalid_argument("chained frames of height " + std::to_string(g.height) +
                                    " have a single window row, which the thesis's host driver cannot chain "
                                    "(it would re-send the preloaded columns of every frame); use height >= 10 "
                                    "or one frame");
    for (size_t f = 0; f < frames_.size(); ++f) {
        const Image& im = *frames_[f];
        if (im.width != g.width || im.height != g.height)
            throw std::invalid_argument("frame " + std::to_string(f) + " is " +
                                        std::to_string(im.width) + "x" + std::to_string(im.height) +
                                        " but the design is built for " + std::to_string(g.width) +
                                        "x" + std::to_string(g.height));
    }
}

void HostDriver::set_frame(int k, const Image* im) {
    if (k < 0 || k >= static_cast<int>(frames_.size()))
        throw std::invalid_argument("host driver: frame " + std::to_string(k) + " of a stream of " +
                                    std::to_string(frames_.size()) + " frames");
    if (im->width != g_.width || im->height != g_.height)
        throw std::invalid_argument("frame " + std::to_string(k) + " is " + std::to_string(im->width) + "x" +
                                    std::to_string(im->height) + " but the design is built for " +
                                    std::to_string(g_.width) + "x" + std::to_string(g_.height));
    frames_[static_cast<std::size_t>(k)] = im;
}

long HostDriver::total_writes() const {
    const long n = static_cast<long>(frames_.size());
    // every frame's body, minus the two preloaded columns of frames 1.., plus their tails
    return n * g_.frame_writes();
}

long HostDriver::total_reads() const {
    // reads in a body: one per column with x = j-5 >= 3 (across rows: also the previous
    // row's last two); counted by running the loop's rule without the pixels.
    const int cols = g_.columns();
    const int rows = g_.rows();
    long per_frame = 0;
    // first row: columns j >= 8 read (x = j-5 >= 3); later rows: j = 0,1 read the previous
    // row's last two windows, j >= 8 as before
    per_frame += static_cast<long>(rows) * (cols - 8 > 0 ? cols - 8 : 0) + static_cast<long>(rows - 1) * 2;
    const long n = static_cast<long>(frames_.size());
    return n * per_frame + (n - 1) * 2;
}

Corner HostDriver::quadrant_centre(const ReadPos& r, int q) const {
    return {r.frame, r.x + ((q & 2) ? dj_ : 0), r.y + ((q & 1) ? di_ : 0)};
}

Corner HostDriver::write_centre(const WritePos& p, int q) const {
    return quadrant_centre(ReadPos{p.frame, p.j - 3, p.i}, q);
}

void HostDriver::decode(const ReadPos& r, std::uint32_t value, std::vector<Corner>& out) const {
    for (int q = 0; q < 4; ++q)
        if ((value >> (3 - q)) & 1U) out.push_back(quadrant_centre(r, q));
}

DriverState HostDriver::state() const {
    DriverState s;
    s.frame = frame_;
    s.i = i_;
    s.j = j_;
    s.k = k_;
    s.in_tail = in_tail_;
    s.tail_col = tail_col_;
    s.preload = preload_;
    s.done = done_;
    for (int n = 0; n < 3; ++n) {
        s.px[n] = px_[n];
        s.py[n] = py_[n];
    }
    s.column_open = column_open_;
    return s;
}

void HostDriver::restore(const DriverState& s) {
    if (s.frame < 0 || s.frame >= static_cast<int>(frames_.size()))
        throw std::invalid_argument("host driver state at frame " + std::to_string(s.frame) + " of a stream of " +
                                    std::to_string(frames_.size()) + " frames");
    frame_ = s.frame;
    i_ = s.i;
    j_ = s.j;
    k_ = s.k;
    in_tail_ = s.in_tail;
    tail_col_ = s.tail_col;
    preload_ = s.preload;
    done_ = s.done;
    for (int n = 0; n < 3; ++n) {
        px_[n] = s.px[n];
        py_[n] = s.py[n];
    }
    column_open_ = s.column_open;
}

namespace {

// The bus word of the four quadrants' pixels at (r0, c): (r0, c) in bits 7..0, then
// (r0 + di, c), (r0, c + dj) and (r0 + di, c + dj).
std::uint32_t bus_word(const Image& im, int r0, int c, int di, int dj) {
    return static_cast<std::uint32_t>(im.at(r0, c)) | static_cast<std::uint32_t>(im.at(r0 + di, c)) << 8 |
           static_cast<std::uint32_t>(im.at(r0, c + dj)) << 16 | static_cast<std::uint32_t>(im.at(r0 + di, c + dj)) << 24;
}

}  // namespace

bool HostDriver::next(BusEvent& ev) {
    if (done_) return false;
    const int last_frame = static_cast<int>(frames_.size()) - 1;
    for (;;) {
        if (!in_tail_) {
            if (!column_open_) {
                // entering column (i_, j_): shift the tracked centres as the host does
                px_[2] = px_[1];
                py_[2] = py_[1];
                px_[1] = px_[0];
                py_[1] = py_[0];
                px_[0] = j_ - 3;
                py_[0] = i_;
                const bool send = i_ > 3 || j_ > 1 || preload_;
                if (send) {
                    if (i_ > 3) preload_ = false;
                    column_open_ = true;
                    k_ = -3;
                } else {
                    // column preloaded by the previous frame's tail: skip it
                    if (++j_ >= g_.columns()) { j_ = 0; ++i_; }
                    continue;
                }
            }
            const Image& im = *frames_[frame_];
            const int r0 = i_ + k_;
            ev.data = bus_word(im, r0, j_, di_, dj_);
            ev.pos = WritePos{frame_, i_, j_, k_, false};
            ev.read.reset();
            if (k_ == 3) {
                column_open_ = false;
                if (px_[2] >= 3 && py_[2] >= 3) ev.read = ReadPos{frame_, px_[2], py_[2]};
                if (++j_ >= g_.columns()) {
                    j_ = 0;
                    if (++i_ >= g_.height / 2) {   // frame body done
                        if (frame_ < last_frame) {
                            in_tail_ = true;
                            tail_col_ = 0;
                            k_ = -3;
                        } else {
                            done_ = true;
                        }
                    }
                }
            } else {
                ++k_;
            }
            return true;
        }
        // tail: the next frame's columns 0 and 1 of its first window row (rows 0..6)
        const Image& nx = *frames_[frame_ + 1];
        const int r0 = k_ + 3;
        const int c = tail_col_;
        ev.data = bus_word(nx, r0, c, di_, dj_);
        ev.pos = WritePos{frame_ + 1, 3, c, k_, true};
        ev.read.reset();
        if (k_ == 3) {
            // after column 0: the window two columns back (px[1]); after column 1: px[0]
            const int slot = tail_col_ == 0 ? 1 : 0;
            ev.read = ReadPos{frame_, px_[slot], py_[slot]};
            if (++tail_col_ == 2) {
                in_tail_ = false;
                ++frame_;
                i_ = 3;
                j_ = 0;
                px_[0] = px_[1] = px_[2] = -1;   // apply() starts with fresh locals
                py_[0] = py_[1] = py_[2] = -1;
            }
            k_ = -3;
        } else {
            ++k_;
        }
        return true;
    }
}

FeedDriver::FeedDriver(const Geometry& g, int frames, FrameAt frame)
    : frame_(std::move(frame)), blank_(g.width, g.height),
      drv_(g, std::vector<const Image*>(static_cast<std::size_t>(frames > 0 ? frames : 0), &blank_)), total_(frames) {}

void FeedDriver::restore(const DriverState& s) {
    if (started_) throw std::logic_error("feed driver: restore after the stream started");
    drv_.restore(s);
}

void FeedDriver::need(int k) {
    if (k >= total_ || k <= newest_) return;
    for (auto it = held_.begin(); it != held_.end();)
        if (it->first < k - 1) {
            drv_.set_frame(it->first, &blank_);
            it = held_.erase(it);
        } else {
            ++it;
        }
    std::shared_ptr<const Image> im = frame_(k);
    drv_.set_frame(k, im.get());
    held_.emplace_back(k, std::move(im));
    newest_ = k;
}

bool FeedDriver::next(BusEvent& ev) {
    if (!started_) {
        started_ = true;
        const DriverState s = drv_.state();
        need(s.frame);
        if (s.in_tail) need(s.frame + 1);
    }
    if (!drv_.next(ev)) return false;
    if (!ev.pos.tail && ev.pos.frame != body_) {   // a body starts: its frame's successor is preloaded at its end
        body_ = ev.pos.frame;
        need(body_ + 1);
    }
    return true;
}

}  // namespace hc
