// first.hpp: one of two headers that include each other (header_includes.cmake's fixture).
#pragma once
#include "b/second.hpp"
#include <vector>
