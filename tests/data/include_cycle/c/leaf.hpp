// leaf.hpp: includes a header of the cycle without being in it (header_includes.cmake's fixture).
#pragma once
#include "../a/first.hpp"
