// catch_session.hpp: Catch2's session for a test executable with a main of its own (the library
// catch_session, which compiles Catch2's implementation once for all test executables).
#pragma once

namespace hc::test {

/// Catch::Session().run(argc, argv): the test cases linked into the executable, chosen and
/// reported by its command line; returns Catch's exit status.
int run_catch(int argc, char* argv[]);

}  // namespace hc::test
