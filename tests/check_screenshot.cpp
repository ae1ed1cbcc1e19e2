// check_screenshot PNG X0 Y0 X1 Y1 MIN_FRACTION MAX_FRACTION [fluid|drawn|edges]
// Counts pixels of a kind in the rectangle [X0, X1] x [Y0, Y1] (fractions of the image, y down) and exits 0
// when their share lies in [MIN_FRACTION, MAX_FRACTION], 1 otherwise (and 2 when the file cannot be read):
// - fluid (default): the demo's first fluid colour, saturated blue, as the spheres draw it;
// - drawn: anything but the background (the clear colour 0.11, 0.12, 0.14), as the surface draws water;
// - edges: a brightness step of more than 12 levels to the right or lower neighbour, both drawn: the
//   outlines of spheres, which a smooth surface lacks.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <stb_image.h>

// check_screenshot --silhouette A.png B.png X0 Y0 X1 Y1 MAX_FRACTION: compares where the two pictures (of one
// size) draw anything in the rectangle (fractions of the image, y down): a drawn pixel of either counts as
// matched when the other draws a pixel within one pixel of it. Exits 0 when at most that fraction of the
// drawn pixels is unmatched (1 otherwise, 2 when a file cannot be read or the sizes differ). Shading may
// differ: it compares the outlines of what is drawn.
int silhouette(char** argv) {
  int wa = 0, ha = 0, wb = 0, hb = 0, channels = 0;
  unsigned char* a = stbi_load(argv[2], &wa, &ha, &channels, 3);
  unsigned char* b = stbi_load(argv[3], &wb, &hb, &channels, 3);
  if (!a || !b || wa != wb || ha != hb) {
    std::fprintf(stderr, "cannot compare %s and %s (unreadable or of different sizes)\n", argv[2], argv[3]);
    if (a) stbi_image_free(a);
    if (b) stbi_image_free(b);
    return 2;
  }
  const double x0 = std::atof(argv[4]), y0 = std::atof(argv[5]), x1 = std::atof(argv[6]), y1 = std::atof(argv[7]);
  const double max_fraction = std::atof(argv[8]);
  const auto drawn = [&](const unsigned char* img, int x, int y) {
    if (x < 0 || y < 0 || x >= wa || y >= ha) return false;
    const unsigned char* p = img + 3 * (std::size_t(y) * std::size_t(wa) + std::size_t(x));
    return std::abs(p[0] - 28) + std::abs(p[1] - 31) + std::abs(p[2] - 36) > 12;  // the clear colour, 0-255
  };
  const auto near = [&](const unsigned char* img, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (drawn(img, x + dx, y + dy)) return true;
    return false;
  };
  long unmatched = 0, total = 0;
  for (int y = int(y0 * ha); y < int(y1 * ha); ++y)
    for (int x = int(x0 * wa); x < int(x1 * wa); ++x) {
      const bool da = drawn(a, x, y), db = drawn(b, x, y);
      if (!da && !db) continue;
      ++total;
      unmatched += (da && !near(b, x, y)) || (db && !near(a, x, y)) ? 1 : 0;
    }
  stbi_image_free(a);
  stbi_image_free(b);
  const double share = total ? double(unmatched) / double(total) : 1.0;
  std::printf("%s against %s: %ld of %ld drawn pixels without a drawn pixel within one pixel in the other (%.2f%%) in "
              "[%.2f, %.2f] x [%.2f, %.2f]; at most %.2f%% expected\n",
              argv[2], argv[3], unmatched, total, 100.0 * share, x0, x1, y0, y1, 100.0 * max_fraction);
  return total > 0 && share <= max_fraction ? 0 : 1;
}

int main(int argc, char** argv) {
  if (argc == 9 && std::string(argv[1]) == "--silhouette") return silhouette(argv);
  const std::string mode = argc == 9 ? argv[8] : "fluid";
  if ((argc != 8 && argc != 9) || (mode != "fluid" && mode != "drawn" && mode != "edges")) {
    std::fprintf(stderr, "usage: check_screenshot PNG X0 Y0 X1 Y1 MIN_FRACTION MAX_FRACTION [fluid|drawn|edges]\n"
                         "       check_screenshot --silhouette A.png B.png X0 Y0 X1 Y1 MAX_FRACTION\n");
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
  auto at = [&](int x, int y) { return px + 3 * (std::size_t(std::min(y, h - 1)) * std::size_t(w) + std::size_t(std::min(x, w - 1))); };
  auto drawn = [&](const unsigned char* p) {
    return std::abs(p[0] - 28) + std::abs(p[1] - 31) + std::abs(p[2] - 36) > 12;  // the clear colour, 0-255
  };
  auto brightness = [](const unsigned char* p) { return (p[0] + p[1] + p[2]) / 3; };
  long fluid = 0, total = 0;
  for (int y = int(y0 * h); y < int(y1 * h); ++y)
    for (int x = int(x0 * w); x < int(x1 * w); ++x) {
      const unsigned char* p = at(x, y);
      const int r = p[0], g = p[1], b = p[2];
      if (mode == "fluid") fluid += (b > r + 40 && b > g + 20) ? 1 : 0;
      if (mode == "drawn") fluid += drawn(p) ? 1 : 0;
      if (mode == "edges") {
        const unsigned char *right = at(x + 1, y), *down = at(x, y + 1);
        const bool step = (drawn(right) && std::abs(brightness(p) - brightness(right)) > 12) ||
                          (drawn(down) && std::abs(brightness(p) - brightness(down)) > 12);
        fluid += drawn(p) && step ? 1 : 0;
      }
      ++total;
    }
  stbi_image_free(px);
  const double share = total ? double(fluid) / double(total) : 0.0;
  std::printf("%s: %ld of %ld pixels %s (%.2f%%) in [%.2f, %.2f] x [%.2f, %.2f]; expected %.2f%% to %.2f%%\n",
              argv[1], fluid, total, mode.c_str(), 100.0 * share, x0, x1, y0, y1, 100.0 * lo, 100.0 * hi);
  return share >= lo && share <= hi ? 0 : 1;
}
