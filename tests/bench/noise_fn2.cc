// noise_fn2.cc - FastNoise2 (Perlin, and its 8-octave fBm at gain 0.5, lacunarity 2) over
// a 2048 x 2048 uniform grid, one thread, the median of REPS fills (CPU time); built by tests/bench/noise when
// FastNoise2 is built (FASTNOISE2_SRC, FASTSIMD_SRC).
//   noise_fn2 KIND CELLS REPS LEVEL   KIND: perlin | fbm8; LEVEL: avx2 | max
// CELLS: lattice cells across the map (Perlin's feature scale is 100 world units).
#include <FastNoise/FastNoise.h>
#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

int main(int argc, char **argv)
{
    const char *kind = argc > 1 ? argv[1] : "fbm8";
    double cells = argc > 2 ? atof(argv[2]) : 20.48;
    int reps = argc > 3 ? atoi(argv[3]) : 5, n = 2048;
    FastSIMD::FeatureSet level = argc > 4 && strcmp(argv[4], "avx2") == 0
                                     ? FastSIMD::FeatureSet::AVX2
                                     : FastSIMD::FeatureSet::Max;
    auto perlin = FastNoise::New<FastNoise::Perlin>(level);
    auto fbm = FastNoise::New<FastNoise::FractalFBm>(level);
    fbm->SetSource(perlin);
    fbm->SetOctaveCount(8);
    fbm->SetGain(0.5f);
    fbm->SetLacunarity(2.0f);
    FastNoise::SmartNode<> gen = strcmp(kind, "perlin") == 0 ? FastNoise::SmartNode<>(perlin)
                                                               : FastNoise::SmartNode<>(fbm);
    float step = (float)(cells * 100.0 / n);
    std::vector<float> img((size_t)n * n);
    std::vector<double> rate;
    double sink = 0;
    for (int r = 0; r < reps; r++) {
        std::clock_t t0 = std::clock(); // CPU time, as noise_bench's one thread
        gen->GenUniformGrid2D(img.data(), 0, 0, n, n, step, step, 1337);
        double s = (double)(std::clock() - t0) / CLOCKS_PER_SEC;
        sink += img[12345];
        rate.push_back((double)n * n / s / 1e6);
    }
    std::sort(rate.begin(), rate.end());
    printf("%.1f\n", rate[rate.size() / 2] + 0 * sink);
    return 0;
}
