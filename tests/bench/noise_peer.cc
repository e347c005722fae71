// noise_peer.cc - libnoise's Perlin module (RidgedMulti for ridged8) over the same
// 2048 x 2048 grid, built by tests/bench/noise.
//   noise_peer KIND REPS   KIND: 2d | 3d | fbm8 | ridged8; prints M samples/s.
#include <libnoise/noise.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

int main(int argc, char **argv)
{
    const char *kind = argc > 1 ? argv[1] : "2d";
    int reps = argc > 2 ? atoi(argv[2]) : 3, n = 2048;
    noise::module::Perlin perlin;
    perlin.SetSeed(1);
    perlin.SetFrequency(1.0);
    perlin.SetNoiseQuality(noise::QUALITY_STD);
    perlin.SetOctaveCount(strcmp(kind, "fbm8") == 0 ? 8 : 1);
    noise::module::RidgedMulti ridged;
    ridged.SetSeed(1);
    ridged.SetFrequency(1.0);
    ridged.SetNoiseQuality(noise::QUALITY_STD);
    ridged.SetOctaveCount(8);
    const noise::module::Module &mod = strcmp(kind, "ridged8") == 0
                                           ? (const noise::module::Module &)ridged
                                           : (const noise::module::Module &)perlin;
    double z = strcmp(kind, "3d") == 0 ? 0.3721 * 8 : 0, best = 0, sink = 0;
    std::vector<float> img((size_t)n * n);
    for (int r = 0; r < reps; r++) {
        auto t0 = std::chrono::steady_clock::now();
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                img[(size_t)y * n + x] =
                    (float)mod.GetValue(8.0 * (x + 0.5) / n, 8.0 * (y + 0.5) / n, z);
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        sink += img[12345];
        if ((double)n * n / s / 1e6 > best)
            best = (double)n * n / s / 1e6;
    }
    printf("%.1f\n", best + 0 * sink);
    return 0;
}
