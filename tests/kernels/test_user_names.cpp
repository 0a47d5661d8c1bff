// A user's own names beside `using namespace vplkit`: the helpers the settings descriptions are
// written with (vplkit/settings.hpp) live in vplkit::schema, so that a user's `struct field`
// (or `above`, `closed_range`, ...) is not ambiguous with them. This file is the test: with the
// helpers in vplkit itself, the declarations below do not compile ("reference to 'field' is
// ambiguous").
#include <doctest/doctest.h>

#include <string>

#include <vplkit/vplkit.hpp>

using namespace vplkit;

// Names a user's program may well have, at global scope.
struct field {
  std::string name;
  int value = 0;
};
struct above {
  double height = 0.0;
};
int closed_range(int low, int high) { return high - low; }
int at_least(int value) { return value; }
int any_finite() { return 7; }
bool no_rules() { return true; }
// vplkit has functions called describe (pass_timer.hpp); a namespace of that name would collide too.
std::string describe(int value) { return std::to_string(value); }

TEST_CASE("a user's struct field and other common names are not ambiguous under using namespace vplkit") {
  const field mine{"radius", 3};
  CHECK(mine.name == "radius");
  CHECK(mine.value == 3);
  CHECK(above{2.0}.height == 2.0);
  CHECK(closed_range(1, 4) == 3);
  CHECK(at_least(5) == 5);
  CHECK(any_finite() == 7);
  CHECK(no_rules());
  CHECK(describe(4) == "4");
  // The library's helpers stay reachable, qualified, and the descriptions built with them work.
  CHECK(schema::closed_range(0, 1).contains(1.0));
  CHECK_FALSE(schema::above(0.0).contains(0.0));
  CHECK(describe_field(&irradiance_settings<float>::min_distance).range.low_open);
  CHECK_FALSE(validate(irradiance_settings<float>{}));
}
