// load_control.hpp: model of rtl/load_control.vhd.
//
// Counts writes within a window row (col, 1..(w/2+3)*7) and rows within a frame (row,
// 1..h/2-3). load = 1 after writes 1..48 of a row and after the last write of every row
// but a frame's last; 0 from write 49 to the end of the row. At the end of a frame load
// stays 0, so the next frame's first columns enter the pipeline.
#pragma once

#include "model/harris/harris_pkg.hpp"

namespace hc {

struct LoadControl {
    int row = 1;
    int col = 1;
    bool load = true;

    void reset() { *this = LoadControl{}; }

    /// One write: the register values after the clock edge.
    LoadControl next(const Geometry& g) const {
        LoadControl n = *this;
        if (col < g.row_writes()) {
            n.load = col < 49;       // the 7x7 window is full after write 49
            n.col = col + 1;
        } else {
            n.col = 1;
            if (row < g.rows()) {
                n.load = true;
                n.row = row + 1;
            } else {
                n.row = 1;           // frame end: load is not raised (thesis behaviour)
            }
        }
        return n;
    }
};

}  // namespace hc
