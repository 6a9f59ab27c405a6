# command_line_thin.cmake: the command line (tools/) only binds flags, calls one library
# function per command and prints: its C++ files hold at most MAX lines in all, and each
# cmd_*.cpp calls a library's run_*_command, itself or through run_quoting_command_line (or,
# for `shard`, the runner) in its callbacks.
#   cmake -DSRC=<source tree> -DMAX=<n> -P command_line_thin.cmake
cmake_policy(VERSION 3.25)
file(GLOB files ${SRC}/tools/*.cpp ${SRC}/tools/*.hpp)
set(total 0)
foreach(f IN LISTS files)
  file(STRINGS ${f} lines)
  list(LENGTH lines n)
  math(EXPR total "${total} + ${n}")
endforeach()
if(total GREATER MAX)
  message(FATAL_ERROR "tools/ holds ${total} lines of C++ (at most ${MAX}): move logic into the libraries")
endif()
file(GLOB commands ${SRC}/tools/cmd_*.cpp)
foreach(f IN LISTS commands)
  file(READ ${f} text)
  if(NOT text MATCHES "run_[a-z_]+_command[(),]" AND NOT text MATCHES "run_worker\\(")
    get_filename_component(name ${f} NAME)
    message(FATAL_ERROR "tools/${name} calls no library's run_*_command")
  endif()
endforeach()
message(STATUS "tools/ holds ${total} lines of C++ (at most ${MAX})")
