// harris-cosim: co-simulation, evaluation and exploration of the Harris co-processor.
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "frames.hpp"

int main(int argc, char** argv) {
    CLI::App app{
        "harris-cosim: proves the VHDL Harris co-processor computes, write by write and bit by bit,\n"
        "what its fixed-point model says, and measures it against OpenCV's Harris."};
    app.require_subcommand(1);
    app.set_version_flag("--version", "harris-cosim 0.1.0");
    hc::tools::add_rtl_command(app);
    hc::tools::add_model_command(app);
    hc::tools::add_golden_command(app);
    hc::tools::add_mutate_command(app);
    hc::tools::add_verilate_command(app);
    hc::tools::add_eval_command(app);
    hc::tools::add_sweep_command(app);
    hc::tools::add_calibrate_command(app);
    hc::tools::add_slam_command(app);
    hc::tools::add_landmarks_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const hc::tools::InputError& e) {
        std::fprintf(stderr, "harris-cosim: error: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "harris-cosim: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "harris-cosim: internal error: %s\n", e.what());
        return 3;
    }
    return 0;
}
