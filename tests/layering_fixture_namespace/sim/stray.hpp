// A simulator header in the core's namespace: tests/layering_test.sh must report it.
#pragma once

namespace msislab {

struct Stray {};

}  // namespace msislab
