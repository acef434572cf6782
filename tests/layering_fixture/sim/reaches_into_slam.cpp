// Not compiled: a fixture for tests/layering_test.sh, which must fail on this include (sim/ may
// not know slam/).
#include "slam/trajectory_slam.hpp"
