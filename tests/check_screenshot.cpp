// check_screenshot PNG X0 Y0 X1 Y1 MIN_FRACTION MAX_FRACTION
// Counts the fluid-coloured pixels (the demo's first fluid colour: saturated blue) in the rectangle
// [X0, X1] x [Y0, Y1] (fractions of the image, y down) and exits 0 when their share lies in
// [MIN_FRACTION, MAX_FRACTION], 1 otherwise (and 2 when the file cannot be read).
#include <cstdio>
#include <cstdlib>

#include <stb_image.h>

int main(int argc, char** argv) {
  if (argc != 8) {
    std::fprintf(stderr, "usage: check_screenshot PNG X0 Y0 X1 Y1 MIN_FRACTION MAX_FRACTION\n");
    return 2;
  }
  int w = 0, h = 0, channels = 0;
  unsigned char* px = stbi_load(argv[1], &w, &h, &channels, 3);
  if (!px) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  const double x0 = std::atof(argv[2]), y0 = std::atof(argv[3]), x1 = std::atof(argv[4]), y1 = std::atof(argv[5]);
  const double lo = std::atof(argv[6]), hi = std::atof(argv[7]);
  long fluid = 0, total = 0;
  for (int y = int(y0 * h); y < int(y1 * h); ++y)
    for (int x = int(x0 * w); x < int(x1 * w); ++x) {
      const unsigned char* p = px + 3 * (std::size_t(y) * std::size_t(w) + std::size_t(x));
      const int r = p[0], g = p[1], b = p[2];
      fluid += (b > r + 40 && b > g + 20) ? 1 : 0;
      ++total;
    }
  stbi_image_free(px);
  const double share = total ? double(fluid) / double(total) : 0.0;
  std::printf("%s: %ld of %ld pixels fluid-coloured (%.2f%%) in [%.2f, %.2f] x [%.2f, %.2f]; expected %.2f%% to %.2f%%\n",
              argv[1], fluid, total, 100.0 * share, x0, x1, y0, y1, 100.0 * lo, 100.0 * hi);
  return share >= lo && share <= hi ? 0 : 1;
}
