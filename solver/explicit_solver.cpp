#include "solver/explicit_solver.hpp"
