// Golden-section search for the minimum of a function of one variable on [low, high]
// (unimodal there: the estimators call it around the best point of a fine grid).
#pragma once

#include <cmath>

namespace tirefe::post {

template <class Function>
double golden_section_minimum(Function f, double low, double high, int iterations = 60) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = low, b = high;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < iterations; ++i) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - ratio * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + ratio * (b - a), f2 = f(x2);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace tirefe::post
