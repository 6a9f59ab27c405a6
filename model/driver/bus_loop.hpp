// bus_loop.hpp: the host-driver loop, written once: a device (the cycle model HarrisTop, the
// Verilator netlist, anything with `write(std::uint32_t)` and `std::uint32_t corner()`) fed
// the bus events of a HostDriver or FeedDriver in the driver's order, each read's corner bits
// decoded to image positions. What a caller does on a write or a read is a set of hooks.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "model/driver/host_driver.hpp"

namespace hc {

/// A caller's hooks into BusLoop::run; derive from it and hide the hooks you need (they are
/// called on the derived type, not virtually). The order per event: more(), the event
/// fetched, before(ev), the device's write, read(...) when the host reads, then after(ev).
struct BusHooks {
    /// Asked before the next event is fetched: false stops the loop there (a run that ends
    /// at a write count), with no frame asked of the driver.
    bool more() { return true; }
    /// The event before its write: false stops the loop with the event held back, so that
    /// the next run starts with it.
    bool before(const BusEvent&) { return true; }
    /// A read after the event's write: the device's corner bits and their image positions.
    void read(const BusEvent&, std::uint32_t /*value*/, const std::vector<Corner>& /*corners*/) {}
    /// After the event's write (and its read).
    void after(const BusEvent&) {}
};

inline const HostDriver& host_of(const HostDriver& d) { return d; }
inline const HostDriver& host_of(const FeedDriver& d) { return d.driver(); }

/// The loop over `Driver` (HostDriver or FeedDriver) into `Device`; both are referenced, and
/// may be restored to a saved state before the first run.
template <class Driver, class Device>
class BusLoop {
public:
    BusLoop(Driver& driver, Device& device) : driver_(driver), device_(device) {}

    /// Runs events until a hook stops the loop (true) or the stream ends (false).
    template <class Hooks>
    bool run(Hooks& h) {
        BusEvent ev;
        for (;;) {
            if (held_) {
                ev = *held_;
                held_.reset();
            } else {
                if (!h.more()) return true;
                if (!driver_.next(ev)) return false;
            }
            if (!h.before(ev)) {
                held_ = ev;
                return true;
            }
            device_.write(ev.data);
            if (ev.read) {
                const std::uint32_t value = device_.corner();
                corners_.clear();
                host_of(driver_).decode(*ev.read, value, corners_);
                h.read(ev, value, corners_);
            }
            h.after(ev);
        }
    }

    const HostDriver& host() const { return host_of(driver_); }

private:
    Driver& driver_;
    Device& device_;
    std::optional<BusEvent> held_;
    std::vector<Corner> corners_;
};

}  // namespace hc
