// Fixture: a presentation command may include report/ (not reported).
#include "report/method_styles.hpp"
