// check_levels_oiio.cpp: OpenImageIO's FLOAT to UINT8 conversion against round(255 e), on
// every float from 0 to just past 1 (docs/numerics.md §11). Prints how many differ.
//   g++ -O2 -ffp-contract=off tools/check_levels_oiio.cpp -o /tmp/check_levels_oiio
//     -lOpenImageIO -lOpenImageIO_Util && /tmp/check_levels_oiio  (one line)
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

int main() {
  const uint32_t end = 0x3f800000u + 1000; // 1.0f and the 1,000 floats above it
  const size_t chunk = size_t(1) << 22;
  std::vector<float> f(chunk);
  std::vector<unsigned char> level(chunk);
  uint64_t checked = 0, differ = 0;
  for (uint32_t base = 0; base < end; base += chunk) {
    size_t n = std::min<size_t>(chunk, end - base);
    for (size_t i = 0; i < n; i++) {
      uint32_t u = base + uint32_t(i);
      std::memcpy(&f[i], &u, 4);
    }
    OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, f.data(), OIIO::TypeDesc::UINT8, level.data(), int(n));
    for (size_t i = 0; i < n; i++, checked++) {
      float e = std::min(f[i], 1.0f); // the writer clamps before OIIO sees a value
      unsigned want = unsigned(std::round(e * 255.0f));
      if (want != level[i] && differ++ < 5) std::printf("%.9g: OIIO %u, round %u\n", f[i], level[i], want);
    }
  }
  std::printf("%llu floats checked, %llu differ\n", (unsigned long long)checked, (unsigned long long)differ);
  return differ != 0;
}
