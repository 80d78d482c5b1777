#pragma once
// Sine, cosine, exponential and logarithm from + − × ÷ and exact roundings alone, so that their bits are
// the same with every compiler and C library: physics calls no libm function whose result may
// differ between libraries (docs/design.md#determinism). Both keep to about 1e-16 relative
// error over the ranges the ocean uses; outside them they stay deterministic and lose accuracy.

#include <cmath>
#include <cstdint>

namespace mane::physics::detail {

struct SineCosine {
  double sine = 0.0;
  double cosine = 1.0;
};

/// sin x and cos x. x is reduced by n·π/2 in Cody and Waite's way, with π/2 split as fdlibm's
/// __ieee754_rem_pio2 splits it (two 33-bit parts and a tail), so n·part is exact for
/// |n| < 2²⁰, that is |x| < 1.6e6; the Taylor series then run to r¹⁷ and r¹⁶ on |r| ≤ π/4,
/// where what they leave out is below 1e-17.
inline SineCosine sineCosine(double x) {
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPiOver2First = 1.57079632673412561417e+00;
  constexpr double kPiOver2Second = 6.07710050630396597660e-11;
  constexpr double kPiOver2Tail = 2.02226624879595063154e-21;
  // floor is an exact rounding: the same bits everywhere.
  const double n = std::floor(x * kTwoOverPi + 0.5);
  const double r = ((x - n * kPiOver2First) - n * kPiOver2Second) - n * kPiOver2Tail;
  const double r2 = r * r;
  const double s =
      r * (1.0 + r2 * (-1.0 / 6.0 +
                       r2 * (1.0 / 120.0 +
                             r2 * (-1.0 / 5040.0 +
                                   r2 * (1.0 / 362880.0 +
                                         r2 * (-1.0 / 39916800.0 +
                                               r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0 +
                                                                                r2 * (1.0 / 355687428096000.0)))))))));
  const double c =
      1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 +
                               r2 * (-1.0 / 720.0 +
                                     r2 * (1.0 / 40320.0 +
                                           r2 * (-1.0 / 3628800.0 +
                                                 r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0 +
                                                                                 r2 * (1.0 / 20922789888000.0))))))));
  // The quadrant n mod 4, for negative n too.
  const auto quadrant = static_cast<std::int64_t>(n) & 3;
  switch (quadrant) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

/// eˣ. x = n·ln 2 + r with ln 2 split as fdlibm's __ieee754_exp splits it, |r| ≤ ln 2 / 2; the
/// Taylor series of eʳ to r¹³ leaves out less than 1e-17, and ldexp scales by 2ⁿ exactly.
/// Below −745 the result is 0.
inline double exponential(double x) {
  if (x < -745.0) return 0.0;
  constexpr double kInverseLn2 = 1.44269504088896338700e+00;
  constexpr double kLn2High = 6.93147180369123816490e-01;
  constexpr double kLn2Low = 1.90821492927058770002e-10;
  const double n = std::floor(x * kInverseLn2 + 0.5);
  const double r = (x - n * kLn2High) - n * kLn2Low;
  double term = 1.0;
  double sum = 1.0;
  for (int i = 1; i <= 13; ++i) {
    term = term * r / static_cast<double>(i);
    sum += term;
  }
  return std::ldexp(sum, static_cast<int>(n));
}

/// ln x for x > 0 (else NaN). frexp splits x exactly into m·2ᵉ with m in [√½, √2); then
/// ln m = 2 artanh s with s = (m − 1)/(m + 1), |s| ≤ 0.172, whose series to s²¹ leaves out
/// less than 1e-17.
inline double logarithm(double x) {
  if (!(x > 0.0)) return std::nan("");
  int exponent = 0;
  double m = std::frexp(x, &exponent);  // m in [½, 1)
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    exponent -= 1;
  }
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double power = s;
  double sum = 0.0;
  for (int k = 1; k <= 21; k += 2) {
    sum += power / static_cast<double>(k);
    power *= s2;
  }
  constexpr double kLn2 = 6.93147180559945309417e-01;
  return 2.0 * sum + static_cast<double>(exponent) * kLn2;
}

}  // namespace mane::physics::detail
