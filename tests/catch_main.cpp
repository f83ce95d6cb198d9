// Catch2's main lives in its own translation unit so that the heavy header compiles once.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
