// A fixture for tests/layering_test.sh (never compiled): a command file that calls another
// command's file, which the check must report (the ctest Architecture.LayeringCatchesCommandCalls).
#include "app/sweep_command.hpp"

#include "app/montecarlo_command.hpp"
