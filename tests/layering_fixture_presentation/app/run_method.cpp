// Fixture: code that runs a method reaching for a method's colour (tests/layering_test.sh).
#include "app/run_method.hpp"
#include "report/method_styles.hpp"

int colour_of_the_method() { return 0; }
