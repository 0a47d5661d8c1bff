// Closed-form configuration factors from the heat-transfer literature, shared by the tests of
// the form factors and of the reference renderer.
#pragma once

#include <cmath>

namespace vplkit::closed_forms {

inline constexpr double pi = 3.14159265358979323846;

// Howell, "A Catalog of Radiation Heat Transfer Configuration Factors" (3rd ed.), factor B-3:
// plane element dA1 to a plane parallel rectangle a x b at distance c, the normal of the element
// passing through a corner of the rectangle; X = a / c, Y = b / c.
inline double parallel_rectangle(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) + y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * pi);
}

// Howell's factor B-2: plane element dA1 to a rectangle a x b in a plane perpendicular to the
// element's, the rectangle's side a lying in the element's plane at distance c, the element
// opposite one end of it; with X = b / a, Y = c / a:
// F = (atan(1 / Y) - Y / sqrt(X^2 + Y^2) atan(1 / sqrt(X^2 + Y^2))) / (2 pi).
inline double perpendicular_rectangle(double a, double b, double c) {
  const double x = b / a, y = c / a;
  return (std::atan(1 / y) - y / std::sqrt(x * x + y * y) * std::atan(1 / std::sqrt(x * x + y * y))) / (2 * pi);
}

}  // namespace vplkit::closed_forms
