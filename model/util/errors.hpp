// errors.hpp: the kinds of failure harris-cosim tells apart, each its own exception type.
//
// Purpose: a library throws the type that says what went wrong; the command line maps each
// type to one exit status in one place (tools/harris_cosim.cpp):
//
//   type              status  meaning
//   MismatchError        1    the design and the model (or a golden file) disagree
//   InputError           2    bad user input: a file, a flag value, a configuration
//   SimulatorError       3    a simulator or tool did not run to its end
//   TranslationFault     4    GHDL's netlist means something else than the VHDL (verilate gate)
//   InternalError        5    a fault of harris-cosim itself (any other exception too)
//
// One type per kind, thrown as it is by every library (no library derives its own).
// A width check inside the model (std::invalid_argument) is an internal fault: user input
// is validated at the boundary that reads it, which throws InputError naming the input.
#pragma once

#include <stdexcept>

namespace hc {

/// The design differs from the model or a reference. Exit status 1.
struct MismatchError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// Bad user input; what() names the input. Exit status 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// A simulator or external tool failed or stopped early. Exit status 3.
struct SimulatorError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// GHDL's synthesised netlist disagrees with GHDL's simulation of the VHDL. Exit status 4.
struct TranslationFault : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// A fault of harris-cosim itself (a broken invariant). Exit status 5.
struct InternalError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The exit statuses, for the one mapping in main and for tests.
namespace exit_status {
inline constexpr int pass = 0;
inline constexpr int mismatch = 1;
inline constexpr int bad_input = 2;
inline constexpr int simulator_failure = 3;
inline constexpr int translation_fault = 4;
inline constexpr int internal_fault = 5;
}  // namespace exit_status

}  // namespace hc
