// Blocks of doubles for the echo physics: SLEEF's vector functions on SSE2's two lanes (every
// x86-64 has them, and the one fixed variant gives the same bits on every such machine), SLEEF's
// scalar functions elsewhere. Only the operations the receiver needs.
#pragma once

#include <cstddef>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <sleef.h>

namespace msislab::sim::lanes {

#if defined(__SSE2__)
using Lanes = __m128d;
inline constexpr std::size_t kLanes = 2;

inline Lanes load(const std::vector<double>& v, std::size_t i) { return _mm_loadu_pd(&v[i]); }
inline void store(Lanes x, std::vector<double>& v, std::size_t i) { _mm_storeu_pd(&v[i], x); }
inline double lane(Lanes x, std::size_t k) {
  double out[kLanes];
  _mm_storeu_pd(out, x);
  return out[k];
}
inline Lanes add(Lanes a, Lanes b) { return _mm_add_pd(a, b); }
inline Lanes add(Lanes a, double b) { return _mm_add_pd(a, _mm_set1_pd(b)); }
inline Lanes sub(Lanes a, Lanes b) { return _mm_sub_pd(a, b); }
inline Lanes mul(Lanes a, Lanes b) { return _mm_mul_pd(a, b); }
inline Lanes mul(Lanes a, double b) { return _mm_mul_pd(a, _mm_set1_pd(b)); }
/// Within 1 ulp (SLEEF's u10 functions).
inline Lanes atan2(Lanes y, Lanes x) { return Sleef_atan2d2_u10sse2(y, x); }
inline Lanes asin(Lanes x) { return Sleef_asind2_u10sse2(x); }
inline Lanes exp(Lanes x) { return Sleef_expd2_u10sse2(x); }
#else
using Lanes = double;
inline constexpr std::size_t kLanes = 1;

inline Lanes load(const std::vector<double>& v, std::size_t i) { return v[i]; }
inline void store(Lanes x, std::vector<double>& v, std::size_t i) { v[i] = x; }
inline double lane(Lanes x, std::size_t) { return x; }
inline Lanes add(Lanes a, double b) { return a + b; }
inline Lanes sub(Lanes a, Lanes b) { return a - b; }
inline Lanes mul(Lanes a, double b) { return a * b; }
inline Lanes atan2(Lanes y, Lanes x) { return Sleef_atan2_u10(y, x); }
inline Lanes asin(Lanes x) { return Sleef_asin_u10(x); }
inline Lanes exp(Lanes x) { return Sleef_exp_u10(x); }
#endif

}  // namespace msislab::sim::lanes
