// Catch2's main for the test executables that have none of their own (the library catch_main).
#include "tests/catch_session.hpp"

int main(int argc, char* argv[]) { return hc::test::run_catch(argc, argv); }
