// Writes the LDI pack seed of the ldi_pack fuzzer (fuzz/corpus/ldi_pack/cohen8-tiny.ldi) with the
// real builder: cohen8 with 3 sunflowers a tile, 1 level, 1 direction, sampled for a 16-pixel
// view so the pack stays a few KB. Usage: ldi_pack_seed OUT.ldi
#include <cstdio>
#include <exception>
#include <vector>

#include "generator/poisson_tiles.h"
#include "generator/tileset.h"
#include "renders/ldi/ldi_build.h"
#include "templates/sunflower.h"

int main(int argc, char** argv) {
  using namespace wangscape;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.ldi\n", argv[0]);
    return 2;
  }
  try {
    PoissonFillOptions fill;
    fill.points_per_tile = 3;
    fill.seed = 5;
    fill.variants = 1;
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), fill);
    const std::vector<Mesh> models = {make_sunflower(1, 0, kSunflowerMinimumTriangleBudget).mesh};
    LdiBuildOptions options;
    options.view.levels = 1;
    options.view.directions = 1;
    options.view.image_width = 16;
    options.shading.ao_rays = 0;
    build_ldi_pack(filled, models, options, argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ldi_pack_seed: %s\n", e.what());
    return 1;
  }
  return 0;
}
