// Sine and cosine of one angle, inline and branch-free, so that a loop over elements
// marked "omp simd" vectorises through them (a call to libm's sin/cos stops it).
//
// The angle is reduced by the nearest multiple n of pi/2 with pi/2 split in two (the
// first part has 33 bits, so n pi/2_1 and x - n pi/2_1 are exact for |n| < 2^20), then
// fdlibm's minimax polynomials for sin and cos on [-pi/4, pi/4] (error below 1e-19)
// give the reduced values, and n mod 4 picks and signs them. Belt rotations of a rolling
// tire reach hundreds of radians: for |x| <= 1e5 the results are within 3e-16 of
// std::sin and std::cos (tests/test_tread_beam.cpp).
#pragma once

namespace tirefe {

struct SineCosine {
  double sin, cos;
};

inline SineCosine sine_cosine(double angle) {
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kHalfPi1 = 1.57079632673412561417e+00;      // the first 33 bits of pi/2
  constexpr double kHalfPi1Tail = 6.07710050650619224932e-11;  // pi/2 - kHalfPi1
  constexpr double kRound = 6755399441055744.0;                // 1.5 * 2^52: x + kRound - kRound rounds x
  const double n = (angle * kTwoOverPi + kRound) - kRound;
  const double x = (angle - n * kHalfPi1) - n * kHalfPi1Tail;  // in [-pi/4, pi/4] (to 1 ulp)
  const double z = x * x, w = z * z;
  // fdlibm __kernel_sin and __kernel_cos (musl's form).
  const double s =
      x + z * x *
              (-1.66666666666666324348e-01 +
               z * ((8.33333333332248946124e-03 + z * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06)) +
                    z * w * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)));
  const double r =
      z * (4.16666666666666019037e-02 + z * (-1.38888888888741095749e-03 + z * 2.48015872894767294178e-05)) +
      w * w * (-2.75573143513906633035e-07 + z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11));
  const double half_z = 0.5 * z, one_less = 1.0 - half_z;
  const double c = one_less + (((1.0 - one_less) - half_z) + z * r);
  // The quadrant q = n mod 4 in {-2, -1, 0, 1, 2}: x + q pi/2 is the angle modulo 2 pi.
  const double q = n - 4.0 * ((0.25 * n + kRound) - kRound);
  const bool odd = q == 1.0 || q == -1.0;
  const double sine = odd ? c : s, cosine = odd ? s : c;
  return {(q < 0.0 || q > 1.5) ? -sine : sine, (q > 0.5 || q < -1.5) ? -cosine : cosine};
}

}  // namespace tirefe
