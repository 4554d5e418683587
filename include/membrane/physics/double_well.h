#pragma once
// The Cahn-Hilliard double well f(phi) = 9/32 (phi^2 - 1)^2 (MODEL.md section 2).
// With this normalisation the sharp-interface line tension is sigma * xi.

namespace Membrane::DoubleWell
{
  inline double value(const double phi) { return 9.0 / 32.0 * (phi * phi - 1) * (phi * phi - 1); }
  inline double derivative(const double phi) { return 9.0 / 8.0 * phi * (phi * phi - 1); }
  inline double second_derivative(const double phi) { return 9.0 / 8.0 * (3 * phi * phi - 1); }
} // namespace Membrane::DoubleWell
