/*
 * swell from C: an FFT ocean, a floating buoy's height, the displaced mesh per frame and one
 * rendered frame into a caller's RGBA8 buffer. Every error is checked and printed.
 *
 * Build and run (from the repository root, after `cargo build --release -p swell-capi`):
 *   cc -std=c99 -Wall -Wextra -I crates/swell-capi/include crates/swell-capi/examples/ocean.c \
 *      -L target/release -lswell -o ocean && LD_LIBRARY_PATH=target/release ./ocean
 * Or with pkg-config after `sh crates/swell-capi/install.sh PREFIX`:
 *   cc ocean.c $(pkg-config --cflags --libs swell) -o ocean
 *
 * It prints, per frame, the time, the buoy's height and the first vertex, with full float precision
 * (the Rust tests compare these numbers with the library's).
 */
#include <stdio.h>
#include <stdlib.h>

#include "swell.h"

/* A scene's TOML text: only [water] matters for the query API; the rest is for the render. */
static const char *SCENE =
    "version = 1\n"
    "[camera]\n"
    "eye = [0.0, 12.0, 60.0]\n"
    "target = [0.0, 0.0, 0.0]\n"
    "[render]\n"
    "width = 96\n"
    "height = 54\n"
    "[water]\n"
    "model = 'fft'\n"
    "size = [64.0, 64.0]\n"
    "cells = [32, 32]\n"
    "grid = 32\n"
    "patch_size = 64.0\n"
    "wind_speed = 12.0\n"
    "choppiness = 1.0\n"
    "foam = true\n"
    "seed = 3\n";

static int fail(const char *what, SwellResult r) {
    fprintf(stderr, "%s failed (code %d): %s\n", what, (int)r, swell_last_error_message());
    return 1;
}

int main(void) {
    printf("swell %s\n", swell_version());

    SwellWater *water = NULL;
    SwellResult r = swell_water_from_toml(SCENE, &water);
    if (r != SWELL_RESULT_OK) return fail("swell_water_from_toml", r);

    size_t rows = 0, cols = 0;
    swell_water_grid_size(water, &rows, &cols);
    size_t n = rows * cols;
    float *positions = malloc(3 * n * sizeof(float));
    float *normals = malloc(3 * n * sizeof(float));
    float *foam = malloc(n * sizeof(float));
    if (!positions || !normals || !foam) return 1;

    /* The buoy and two other floating points, (x, z) pairs in metres. */
    const float points[6] = {3.0f, -4.0f, 10.0f, 7.5f, -20.0f, 12.25f};
    float heights[3];
    float point_normals[9];

    for (int frame = 0; frame < 3; frame++) {
        double t = frame / 24.0 + 1.0;
        /* The displaced mesh for this frame, then queries at the same time: one synthesis. */
        r = swell_water_displace(water, t, positions, 3 * n, normals, 3 * n);
        if (r != SWELL_RESULT_OK) { fail("swell_water_displace", r); break; }
        r = swell_water_heights(water, t, points, 6, heights, 3);
        if (r != SWELL_RESULT_OK) { fail("swell_water_heights", r); break; }
        r = swell_water_normals(water, t, points, 6, point_normals, 9);
        if (r != SWELL_RESULT_OK) { fail("swell_water_normals", r); break; }
        bool has_foam = false;
        r = swell_water_foam(water, t, foam, n, &has_foam);
        if (r != SWELL_RESULT_OK) { fail("swell_water_foam", r); break; }
        printf("t %.9g buoy %.9g %.9g %.9g vertex0 %.9g %.9g %.9g foam %d normal %.4f %.4f %.4f\n", t,
               heights[0], heights[1], heights[2], positions[0], positions[1], positions[2], (int)has_foam,
               point_normals[0], point_normals[1], point_normals[2]);
    }

    /* An engine 10^6 m from its origin asks in double precision: the FFT ocean repeats every
     * patch_size (64 m), so the buoy 15625 patches east floats exactly as the one at home. */
    const double far_points[4] = {3.0, -4.0, 3.0 + 64.0 * 15625.0, -4.0};
    double far_heights[2];
    r = swell_water_heights_f64(water, 1.0, far_points, 4, far_heights, 2);
    if (r != SWELL_RESULT_OK) return fail("swell_water_heights_f64", r);
    printf("far buoy %.9g %.9g\n", far_heights[0], far_heights[1]);

    /* Errors are codes with a message naming the parameter, its value and the valid range. */
    r = swell_water_displace(water, 0.0, positions, 3 * n - 1, normals, 3 * n);
    printf("short buffer -> %d: %s\n", (int)r, swell_last_error_message());
    SwellWater *bad = NULL;
    r = swell_water_from_toml("version = 1\n[camera]\neye = [0.0, 1.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n"
                              "[water]\nmodel = 'fft'\ngrid = 100\n", &bad);
    printf("bad scene -> %d: %s\n", (int)r, swell_last_error_message());

    /* A rendered frame into our own buffer. */
    SwellScene *scene = NULL;
    r = swell_scene_from_toml(SCENE, &scene);
    if (r != SWELL_RESULT_OK) return fail("swell_scene_from_toml", r);
    uint32_t width = 0, height = 0;
    swell_scene_image_size(scene, &width, &height);
    size_t bytes = 4u * width * height;
    unsigned char *rgba = malloc(bytes);
    if (!rgba) return 1;
    r = swell_scene_render_rgba8(scene, 1.0, rgba, bytes);
    if (r != SWELL_RESULT_OK) return fail("swell_scene_render_rgba8", r);
    unsigned long sum = 0;
    for (size_t k = 0; k < bytes; k++) sum += rgba[k];
    printf("rendered %ux%u, byte sum %lu\n", width, height, sum);

    free(rgba);
    swell_scene_destroy(scene);
    free(foam);
    free(normals);
    free(positions);
    swell_water_destroy(water);
    return 0;
}
