// second.hpp: includes first.hpp, which includes it (header_includes.cmake's fixture).
#pragma once
#include "a/first.hpp"
