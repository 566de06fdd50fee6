/*
 * swell from C: floating bodies (issue 34). A crate rides a Gerstner sea; after a second a barrel
 * (from a [[body]] TOML snippet) and a ball (from parameters) are dropped beside it, and after two
 * the crate is pushed east by a thrust. Every error is checked and printed.
 *
 * Build and run (from the repository root, after `cargo build --release -p swell-capi`):
 *   cc -std=c99 -Wall -Wextra -I crates/swell-capi/include crates/swell-capi/examples/bodies.c \
 *      -L target/release -lswell -o bodies && LD_LIBRARY_PATH=target/release ./bodies
 * Or with pkg-config after `sh crates/swell-capi/install.sh PREFIX`:
 *   cc bodies.c $(pkg-config --cflags --libs swell) -o bodies
 *
 * It prints, every half second, each body's name, position (x, y, z, m) and rotation (quaternion
 * x, y, z, w) with full double precision (the Rust tests compare these numbers with the library's).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "swell.h"

/* Two Gerstner waves over a 60 m patch, and a crate of pine (500 kg/m³) half a metre up. */
static const char *SCENE =
    "version = 1\n"
    "[water]\n"
    "model = 'gerstner'\n"
    "size = [60.0, 60.0]\n"
    "cells = [16, 16]\n"
    "extent = 'patch'\n"
    "[[water.waves]]\n"
    "amplitude = 0.4\n"
    "wavelength = 20.0\n"
    "speed = 5.6\n"
    "direction = [1.0, 0.3]\n"
    "steepness = 0.5\n"
    "[[water.waves]]\n"
    "amplitude = 0.15\n"
    "wavelength = 8.0\n"
    "speed = 3.5\n"
    "direction = [0.6, -0.8]\n"
    "steepness = 0.4\n"
    "[[body]]\n"
    "name = 'crate'\n"
    "shape = 'box'\n"
    "size = [1.0, 0.6, 1.5]\n"
    "density = 500.0\n"
    "position = [0.0, 0.5, 0.0]\n";

/* A body added into the running scene: one [[body]] table as a scene file holds it. */
static const char *BARREL =
    "[[body]]\n"
    "name = 'barrel'\n"
    "shape = 'capsule'\n"
    "size = [0.3, 0.8]\n"
    "density = 400.0\n"
    "position = [-2.0, 1.5, 1.0]\n"
    "rotation_deg = [30.0, 0.0, 0.0]\n";

/* At most this many bodies here: the crate, the barrel and the ball. */
#define MAX_BODIES 8

static int fail(const char *what, SwellResult r) {
    fprintf(stderr, "%s failed (code %d): %s\n", what, (int)r, swell_last_error_message());
    return 1;
}

/* Prints the bodies' poses at time t, one line each. */
static SwellResult print_poses(SwellScene *scene, double t) {
    size_t n = 0;
    SwellResult r = swell_scene_body_count(scene, &n);
    if (r != SWELL_RESULT_OK) return r;
    if (n > MAX_BODIES) return SWELL_RESULT_INVALID_ARGUMENT;
    double positions[3 * MAX_BODIES], rotations[4 * MAX_BODIES];
    /* The lengths are exact: 3 and 4 doubles per body. */
    r = swell_scene_body_poses(scene, t, positions, 3 * n, rotations, 4 * n);
    if (r != SWELL_RESULT_OK) return r;
    for (size_t k = 0; k < n; k++) {
        /* Names are asked twice: once for the size, once into a buffer of that size. */
        size_t size = 0;
        r = swell_scene_body_name(scene, k, NULL, 0, &size);
        if (r != SWELL_RESULT_OK) return r;
        char *name = malloc(size);
        if (!name) return SWELL_RESULT_INVALID_ARGUMENT;
        r = swell_scene_body_name(scene, k, name, size, &size);
        if (r == SWELL_RESULT_OK) {
            const double *p = positions + 3 * k, *q = rotations + 4 * k;
            printf("t %.17g %s %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", t, name, p[0], p[1], p[2], q[0],
                   q[1], q[2], q[3]);
        }
        free(name);
        if (r != SWELL_RESULT_OK) return r;
    }
    return SWELL_RESULT_OK;
}

int main(void) {
    SwellScene *scene = NULL;
    SwellResult r = swell_scene_from_toml(SCENE, &scene);
    if (r != SWELL_RESULT_OK) return fail("swell_scene_from_toml", r);

    size_t crate = 0;
    r = swell_scene_body_index(scene, "crate", &crate);
    if (r != SWELL_RESULT_OK) return fail("swell_scene_body_index", r);

    /* An engine at 24 fps for four seconds; the bodies step at 120 Hz whatever the frame rate. */
    for (int frame = 0; frame <= 96; frame++) {
        double t = frame / 24.0;
        r = swell_scene_advance(scene, t);
        if (r != SWELL_RESULT_OK) return fail("swell_scene_advance", r);
        if (frame % 12 == 0) {
            r = print_poses(scene, t);
            if (r != SWELL_RESULT_OK) return fail("print_poses", r);
        }
        if (frame == 24) {
            /* Dropped at t = 1 s: held still until the next body step, then falling free. */
            size_t barrel = 0, ball = 0;
            r = swell_scene_add_body_toml(scene, BARREL, &barrel);
            if (r != SWELL_RESULT_OK) return fail("swell_scene_add_body_toml", r);
            const double radius[1] = {0.25};
            r = swell_scene_add_body(scene, "ball", "sphere", radius, 1, 300.0, 2.0, 1.5, 1.0, &ball);
            if (r != SWELL_RESULT_OK) return fail("swell_scene_add_body", r);
            printf("added barrel %zu ball %zu\n", barrel, ball);
        }
        if (frame == 48) {
            /* 400 N east on the crate from t = 2 s on. */
            r = swell_scene_set_body_thrust(scene, crate, 400.0, 0.0, 0.0);
            if (r != SWELL_RESULT_OK) return fail("swell_scene_set_body_thrust", r);
        }
    }

    /* Errors are codes with a message naming the argument, its value and the valid range; a
     * refused call writes nothing. */
    double positions[3 * MAX_BODIES], rotations[4 * MAX_BODIES];
    r = swell_scene_body_poses(scene, NAN, positions, 9, rotations, 12);
    printf("nan time -> %d: %s\n", (int)r, swell_last_error_message());
    r = swell_scene_body_poses(scene, 4.0, positions, 8, rotations, 12);
    printf("short buffer -> %d: %s\n", (int)r, swell_last_error_message());
    r = swell_scene_add_body_toml(scene, "[[body]]\nshape = 'box'\nsize = [1.0, 0.5]\n", NULL);
    printf("bad body -> %d: %s\n", (int)r, swell_last_error_message());
    r = swell_scene_set_body_thrust(scene, 3, 1.0, 0.0, 0.0);
    printf("bad index -> %d: %s\n", (int)r, swell_last_error_message());

    swell_scene_destroy(scene);
    return 0;
}
