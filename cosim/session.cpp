#include "cosim/session.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace hc::cosim {

Session::Session(RunConfig cfg) : cfg_(std::move(cfg)), cmp_(cfg_.formats) {
    frames_ = read_frames(cfg_.frames_file);
    std::vector<const Image*> ptrs;
    for (const auto& f : frames_) ptrs.push_back(&f);
    driver_ = std::make_unique<HostDriver>(cfg_.geometry, ptrs);
    model_ = std::make_unique<HarrisTop>(cfg_.geometry, cfg_.formats);
    corners_per_frame_.assign(frames_.size(), 0);
    if (!cfg_.reads_file.empty()) {
        reads_out_.open(cfg_.reads_file + ".part");
        if (!reads_out_) throw std::runtime_error("cannot write '" + cfg_.reads_file + ".part'");
        reads_out_ << "write,frame,x,y,value\n";
    }
    start_ = last_progress_ = std::chrono::steady_clock::now();
}

void Session::check_design(int obs_w, const std::vector<long>& got) const {
    const auto want = generics(cfg_.geometry, cfg_.formats);
    if (got.size() != want.size())
        throw std::invalid_argument("testbench handed over " + std::to_string(got.size()) + " generics, expected " +
                                    std::to_string(want.size()));
    for (size_t k = 0; k < want.size(); ++k)
        if (want[k].second != got[k])
            throw std::invalid_argument("testbench generic " + want[k].first + " = " + std::to_string(got[k]) +
                                        " but the run is configured for " + std::to_string(want[k].second));
    if (obs_w != cmp_.width())
        throw std::invalid_argument("observation port is " + std::to_string(obs_w) +
                                    " bits but the C++ layout (model/harris/observation.hpp) has " +
                                    std::to_string(cmp_.width()));
}

Command Session::next() {
    if (stop_) return Command::end;
    if (cfg_.idle_every > 0 && since_idle_ >= cfg_.idle_every) {
        since_idle_ = 0;
        idle_now_ = true;
        return Command::idle;
    }
    idle_now_ = false;
    if (cfg_.max_writes > 0 && model_->writes() >= cfg_.max_writes) return Command::end;
    if (!driver_->next(ev_)) return Command::end;
    model_->write(ev_.data);       // the model's post-edge state, compared after the RTL's edge
    ++since_idle_;
    positions_.emplace_back(model_->writes(), ev_.pos);
    if (positions_.size() > 64) positions_.pop_front();
    return Command::write;
}

void Session::record_read(const std::uint8_t* codes) {
    // the host reads the corner port after the write; take the RTL's bits
    const int corner_field = static_cast<int>(cmp_.layout().size()) - 1;
    int e = 0;
    while (cmp_.element_field(e) != corner_field) ++e;
    std::uint32_t value = 0;
    bool meta = false;
    for (int b = 0; b < 32; ++b) {
        const std::uint8_t c = codes[cmp_.element_offset(e) + b];
        if (c == SL_1) value |= 1U << (31 - b);
        else if (c != SL_0) meta = true;
    }
    ++reads_;
    if (meta || value != model_->corner()) ++read_mismatches_;
    const ReadPos& r = *ev_.read;
    std::vector<Corner> cs;
    driver_->decode(r, value, cs);
    if (r.frame >= 0 && r.frame < static_cast<int>(corners_per_frame_.size()))
        corners_per_frame_[r.frame] += static_cast<long>(cs.size());
    if (reads_out_.is_open())
        reads_out_ << model_->writes() << ',' << r.frame << ',' << r.x << ',' << r.y << ',' << value << '\n';
}

bool Session::observe(const std::uint8_t* codes) {
    ++cycles_;
    if (idle_now_) ++idles_;
    phase_ = Phase::after_edge;
    scratch_.clear();
    FlatObservation flat;
    if (cfg_.compare_all) {
        flat = flatten(model_->observe(), cfg_.formats);
        cmp_.compare(codes, flat, model_->writes(), scratch_);
    }
    if (!idle_now_ && ev_.read) {
        const long before = read_mismatches_;
        record_read(codes);
        if (!cfg_.compare_all && read_mismatches_ != before) {
            // reads-only mode: the corner port is the one signal compared
            flat = flatten(model_->observe(), cfg_.formats);
            cmp_.compare(codes, flat, model_->writes(), scratch_);
            std::erase_if(scratch_, [&](const Mismatch& m) { return cmp_.layout()[m.field].name != "corner"; });
        }
    }
    return record(codes, flat);
}

bool Session::observe_held(const std::uint8_t* codes, bool after_reset) {
    // every register, in either comparison mode: the testbench calls this after reset and,
    // between edges, only when the port changed without an edge
    phase_ = after_reset ? Phase::after_reset : Phase::clock_low;
    scratch_.clear();
    FlatObservation flat = flatten(model_->observe(), cfg_.formats);
    cmp_.compare(codes, flat, model_->writes(), scratch_);
    if (scratch_.empty()) return stop_;
    return record(codes, flat);
}

bool Session::record(const std::uint8_t* codes, FlatObservation& flat) {
    if (!cfg_.compare_all && first_report_.empty() && scratch_.empty()) {
        progress(false);   // reads-only mode keeps no history until something differs
        return stop_;
    }
    if (flat.bits.empty()) flat = flatten(model_->observe(), cfg_.formats);
    CycleRecord rec{model_->writes(), idle_now_, !scratch_.empty(),
                    std::vector<std::uint8_t>(codes, codes + cmp_.width()), flat};
    if (post_left_ > 0 && !vcd_done_) {
        vcd_cycles_.push_back(rec);   // a cycle after the first mismatch
        --post_left_;
    } else {
        history_.push_back(std::move(rec));
        if (static_cast<int>(history_.size()) > cfg_.pre_mismatch) history_.pop_front();
    }

    if (!scratch_.empty()) {
        ++mismatching_cycles_;
        mismatched_elements_ += static_cast<long>(scratch_.size());
        std::map<std::string, bool> seen;
        int first_stage = 1 << 30;
        for (const auto& m : scratch_) {
            const std::string& st = cmp_.layout()[m.field].stage;
            if (m.metavalue) ++metavalue_elements_;
            ++stage_elements_[st];
            if (!seen[st]) {
                seen[st] = true;
                ++stage_cycles_[st];
            }
            first_stage = std::min(first_stage, cmp_.stage_index(m.field));
        }
        ++first_stage_cycles_[stage_order()[first_stage]];
        if (first_report_.empty()) {
            first_stage_ = stage_order()[first_stage];
            first_write_ = model_->writes();
            first_report_ = describe(scratch_, model_->writes(), first_signal_);
            std::fprintf(stderr, "%s", first_report_.c_str());
            vcd_cycles_.assign(history_.begin(), history_.end());
            history_.clear();
            post_left_ = cfg_.post_mismatch;
        }
    }
    if (post_left_ == 0 && !vcd_done_) {
        vcd_done_ = true;
        if (!cfg_.keep_going) stop_ = true;
    }
    progress(false);
    return stop_;
}

std::string Session::describe(const std::vector<Mismatch>& ms, long write, std::string& signal) const {
    // pick the first mismatch of the earliest stage
    const Mismatch* first = &ms.front();
    for (const auto& m : ms)
        if (cmp_.stage_index(m.field) < cmp_.stage_index(first->field)) first = &m;
    const ObsField& f = cmp_.layout()[first->field];
    const WritePos* wp = nullptr;
    for (const auto& [n, p] : positions_)
        if (n == write) wp = &p;

    // which window the stage holds
    const StageTags& tg = model_->tags();
    const WindowTag* tag = nullptr;
    if (f.stage == "input_converter_mux" && f.name == "icm") tag = &tg.window;
    else if (f.stage == "sobel_x" || f.stage == "sobel_y") tag = &tg.sobel;
    else if (f.stage == "m_products") tag = &tg.m;
    else if (f.stage == "block_filter") tag = &tg.block;
    else if (f.stage == "harris_response") tag = &tg.response;
    else if (f.name == "trm" || f.stage == "local_maximum") tag = &tg.thresholded;

    std::ostringstream o;
    o << "\n=== RTL/model MISMATCH ===\n";
    o << "  write      : " << write << (idle_now_ ? " (after an idle cycle)" : "") << "\n";
    if (phase_ == Phase::after_reset)
        o << "  when       : after reset, before the first clock edge (a reset value differs)\n";
    else if (phase_ == Phase::clock_low)
        o << "  when       : while the clock was low after this write (a register changed without a rising edge)\n";
    if (wp)
        o << "  bus cycle  : frame " << wp->frame << (wp->tail ? " (preload of the next frame)" : "")
          << ", window row i=" << wp->i << ", column j=" << wp->j << ", k=" << wp->k << "\n";
    o << "  stage      : " << f.stage << " (first mismatching stage on this write)\n";
    signal = cmp_.element_name(first->field, first->i, first->j);
    o << "  signal     : " << signal << "  [" << f.width << "-bit "
      << (f.is_signed ? "signed" : "unsigned") << "]\n";
    if (tag && tag->valid()) {
        const WritePos* tp = nullptr;
        for (const auto& [n, p] : positions_)
            if (n == tag->write) tp = &p;
        if (tp) {
            const Corner c = driver_->write_centre(*tp, tag->quadrant);
            o << "  window     : quadrant " << tag->quadrant << ", centre pixel (x=" << c.x << ", y=" << c.y
              << ") of frame " << c.frame << " (column completed at write " << tag->write << ")\n";
        }
    } else if (tag) {
        o << "  window     : none (reset or zero window in this register)\n";
    }
    if (first->model_undefined) {
        o << "  expected   : U (undefined in the model)\n";
    } else {
        o << "  expected   : " << cmp_.format_value(first->field, first->expected) << "\n";
    }
    if (first->metavalue) o << "  actual     : " << first->actual << "  (METAVALUE)\n";
    else {
        std::uint64_t bits = 0;
        for (char ch : first->actual) bits = (bits << 1) | (ch == '1' ? 1U : 0U);
        o << "  actual     : " << cmp_.format_value(first->field, bits) << "  bits " << first->actual << "\n";
    }
    std::map<std::string, int> per_signal;
    for (const auto& m : ms) ++per_signal[cmp_.layout()[m.field].name];
    o << "  this write : " << ms.size() << " element(s) differ:";
    for (const auto& [s, n] : per_signal) o << " " << s << "x" << n;
    o << "\n";
    o << "==========================\n";
    return o.str();
}

void Session::progress(bool final) {
    if (!cfg_.progress) return;
    const auto now = std::chrono::steady_clock::now();
    if (!final && now - last_progress_ < std::chrono::seconds(2)) return;
    last_progress_ = now;
    const double secs = std::chrono::duration<double>(now - start_).count();
    const long total = cfg_.max_writes > 0 ? std::min(cfg_.max_writes, driver_->total_writes()) : driver_->total_writes();
    const long w = model_->writes();
    const double rate = secs > 0 ? static_cast<double>(cycles_) / secs : 0.0;
    const int frame = positions_.empty() ? 0 : positions_.back().second.frame;
    std::fprintf(stderr, "[cosim] frame %d/%zu  write %ld/%ld (%.1f%%)  %.0f cycles/s  mismatches %ld  ETA %.0f s\n",
                 frame + 1, frames_.size(), w, total, total ? 100.0 * static_cast<double>(w) / static_cast<double>(total) : 0.0,
                 rate, mismatching_cycles_, rate > 0 ? static_cast<double>(total - w) / rate : 0.0);
}

int Session::close() {
    progress(true);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!first_report_.empty() && !cfg_.vcd_file.empty()) {
        if (!vcd_done_) vcd_done_ = true;
        write_vcd(cfg_.vcd_file, cmp_, vcd_cycles_);
    }
    if (reads_out_.is_open()) {
        reads_out_.close();
        std::rename((cfg_.reads_file + ".part").c_str(), cfg_.reads_file.c_str());
    }
    const bool complete = !stop_ && (cfg_.max_writes == 0 || model_->writes() >= std::min(cfg_.max_writes, driver_->total_writes()));
    Summary sm;
    sm.backend = cfg_.backend;
    sm.geometry = cfg_.geometry;
    sm.formats = cfg_.formats;
    for (size_t k = 0; k < frames_.size(); ++k) {
        sm.frame_names.push_back(k < cfg_.frame_names.size() ? cfg_.frame_names[k] : "");
        sm.corners_per_frame.push_back(corners_per_frame_[k]);
        sm.corners += corners_per_frame_[k];
    }
    sm.complete = complete;
    sm.writes = model_->writes();
    sm.writes_in_stream = driver_->total_writes();
    sm.idle_cycles = idles_;
    sm.cycles = cycles_;
    sm.reads = reads_;
    sm.read_mismatches = read_mismatches_;
    sm.compare_all = cfg_.compare_all;
    sm.signals_compared_per_cycle = cfg_.compare_all ? cmp_.elements() : 1;
    sm.bits_compared_per_cycle = cfg_.compare_all ? cmp_.width() : 32;
    std::map<std::string, long> per_stage_elements;
    for (const auto& f : cmp_.layout()) per_stage_elements[f.stage] += f.elements();
    for (const auto& st : stage_order())
        sm.stages.push_back({st, per_stage_elements[st], stage_cycles_[st], stage_elements_[st], first_stage_cycles_[st]});
    sm.mismatching_cycles = mismatching_cycles_;
    sm.mismatching_elements = mismatched_elements_;
    sm.metavalue_elements = metavalue_elements_;
    sm.wall_seconds = secs;
    sm.cycles_per_second = secs > 0 ? static_cast<double>(cycles_) / secs : 0.0;
    if (!first_report_.empty())
        sm.first_mismatch = FirstMismatch{first_write_, first_stage_, first_signal_, first_report_, cfg_.vcd_file};
    const int status = mismatching_cycles_ > 0 ? 1 : 0;
    if (!cfg_.summary_file.empty()) {
        const std::string tmp = cfg_.summary_file + ".part";
        std::ofstream o(tmp);
        o << to_json(sm);
        o.close();
        if (!o) throw std::runtime_error("cannot write summary '" + cfg_.summary_file + "'");
        std::rename(tmp.c_str(), cfg_.summary_file.c_str());
    }
    return status;
}

}  // namespace hc::cosim
