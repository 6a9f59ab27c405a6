// harris-cosim: co-simulation, evaluation and exploration of the Harris co-processor.
//
// The one place where failures become exit statuses (model/util/errors.hpp):
//   0 pass, 1 mismatch, 2 bad input (including every flag error CLI11 reports),
//   3 simulator failure, 4 translation fault, 5 internal fault.
#include <cstdio>
#include <exception>

#include "tools/commands.hpp"
#include "model/util/errors.hpp"

namespace {
int report(const char* kind, const std::exception& e, int status) {
    std::fprintf(stderr, "harris-cosim: %s: %s\n", kind, e.what());
    return status;
}
}  // namespace

int main(int argc, char** argv) {
    namespace st = hc::exit_status;
    CLI::App app{
        "harris-cosim: proves the VHDL Harris co-processor computes, write by write and bit by bit,\n"
        "what its fixed-point model says, and measures it against OpenCV's Harris.\n"
        "Exit status: 0 pass, 1 mismatch, 2 bad input, 3 simulator failure, 4 translation fault, 5 internal fault."};
    app.require_subcommand(1);
    app.set_version_flag("--version", "harris-cosim " HC_VERSION);
    namespace t = hc::tools;
    t::add_commands(app);
    t::set_program_path(argc > 0 ? argv[0] : nullptr);
    t::set_command_line(argc, argv);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {   // --help, --version
        return app.exit(e);
    } catch (const CLI::RuntimeError& e) {   // a command's own status, as CLI11 carries it
        return e.get_exit_code();
    } catch (const CLI::ParseError& e) {   // a flag CLI11 rejects is bad input
        app.exit(e);
        return st::bad_input;
    } catch (const hc::MismatchError& e) {
        return report("mismatch", e, st::mismatch);
    } catch (const hc::InputError& e) {
        return report("error", e, st::bad_input);
    } catch (const hc::SimulatorError& e) {
        return report("simulator failure", e, st::simulator_failure);
    } catch (const hc::TranslationFault& e) {
        return report("translation fault", e, st::translation_fault);
    } catch (const std::exception& e) {   // InternalError and anything unforeseen
        return report("internal fault", e, st::internal_fault);
    }
    return st::pass;
}
