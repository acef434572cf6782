// A core header in a folder's namespace: tests/layering_test.sh must report it; the helper
// namespace below it is allowed.
#pragma once

namespace msislab::slam {

struct Nested {};

}  // namespace msislab::slam

namespace msislab::detail_of_slam {

struct Helper {};

}  // namespace msislab::detail_of_slam
