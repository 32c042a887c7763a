/* ray_cast.c -- ray casting through the C interface of pqp-rs: renders a model as text by casting
 * one ray per character from a camera in front of it, first one call per ray (pqp_ray_cast), then
 * all rays in one call on every core (pqp_ray_cast_batch), and checks that both agree.
 *
 * Usage: ray_cast [model.tris]   (default: examples/models/bunny.tris)
 * A .tris file holds the triangle count n, then n triangles as nine numbers x1 y1 z1 ... z3. */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Where the default models are: the build gives the absolute path of examples/models, so the
 * program finds them from any working directory. */
#ifndef PQP_MODELS_DIR
#define PQP_MODELS_DIR "examples/models"
#endif

enum { W = 72, H = 36 };

/* Reads a .tris file into a new built model (triangle ids are indices), or returns NULL. */
static pqp_model *load(const char *path)
{
    FILE *f = fopen(path, "r");
    pqp_model *m = NULL;
    int n = 0, i, k, ok = 1;
    if (!f) {
        fprintf(stderr, "cannot open %s\n", path);
        return NULL;
    }
    if (fscanf(f, "%d", &n) == 1 && n > 0 && (m = pqp_model_create()) != NULL) {
        pqp_model_begin(m, n);
        for (i = 0; i < n && ok; i++) {
            double p[9];
            for (k = 0; k < 9 && ok; k++) ok = fscanf(f, "%lf", &p[k]) == 1;
            ok = ok && pqp_model_add_tri(m, p, p + 3, p + 6, i) == PQP_OK;
        }
        ok = ok && pqp_model_end(m) == PQP_OK;
    }
    fclose(f);
    if (!m || !ok) {
        fprintf(stderr, "%s: not a valid .tris file\n", path);
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : PQP_MODELS_DIR "/bunny.tris";
    /* The model as it is (the bunny fits in [-0.8, 0.8]^2 x [-0.6, 0.6]), seen from z = 3. */
    const double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T[3] = {0, 0, 0};
    static double origins[3 * W * H], directions[3 * W * H];
    static pqp_ray_hit hits[W * H], again[W * H];
    pqp_model *m = load(path);
    int x, y, i, rc, hit_count = 0, differ = 0;
    double tmin = INFINITY, tmax = 0;
    if (!m) return 1;

    /* An orthographic camera: parallel rays along -z over the square [-1, 1]^2 (rays need not be
     * unit: these have length 0.5, so t counts half units). */
    for (y = 0; y < H; y++) {
        for (x = 0; x < W; x++) {
            double *o = origins + 3 * (y * W + x), *d = directions + 3 * (y * W + x);
            o[0] = -1.0 + 2.0 * (x + 0.5) / W;
            o[1] = 1.0 - 2.0 * (y + 0.5) / H;
            o[2] = 3.0;
            d[0] = d[1] = 0.0;
            d[2] = -0.5;
        }
    }
    for (i = 0; i < W * H; i++) {
        rc = pqp_ray_cast(&hits[i], R, T, m, origins + 3 * i, directions + 3 * i, INFINITY);
        if (rc != PQP_OK) {
            fprintf(stderr, "pqp_ray_cast: %s\n", pqp_error_string(rc));
            pqp_model_destroy(m);
            return 1;
        }
        if (hits[i].triangle >= 0) {
            hit_count++;
            if (hits[i].t < tmin) tmin = hits[i].t;
            if (hits[i].t > tmax) tmax = hits[i].t;
        }
    }
    /* The same rays in one call, on every core: the same answers. */
    rc = pqp_ray_cast_batch(again, W * H, R, T, m, origins, directions, INFINITY, 0);
    if (rc != PQP_OK) {
        fprintf(stderr, "pqp_ray_cast_batch: %s\n", pqp_error_string(rc));
        pqp_model_destroy(m);
        return 1;
    }
    for (i = 0; i < W * H; i++)
        differ += again[i].triangle != hits[i].triangle || !(again[i].t == hits[i].t ||
                                                              again[i].triangle < 0);

    /* Nearer is darker; the shade also follows the normal's tilt towards the camera. */
    for (y = 0; y < H; y++) {
        char line[W + 1];
        for (x = 0; x < W; x++) {
            const pqp_ray_hit *h = &hits[y * W + x];
            static const char shades[] = "#%*+=-:.";
            if (h->triangle < 0) {
                line[x] = ' ';
            } else {
                double depth = tmax > tmin ? (h->t - tmin) / (tmax - tmin) : 0.0;
                double facing = fabs(h->normal[2]);
                int s = (int)(4.0 * depth + 4.0 * (1.0 - facing));
                line[x] = shades[s < 0 ? 0 : s > 7 ? 7 : s];
            }
        }
        line[W] = '\0';
        printf("%s\n", line);
    }
    printf("%d of %d rays hit %s (t from %.4f to %.4f); batch and single calls %s\n", hit_count,
           W * H, path, tmin, tmax, differ ? "DIFFER" : "agree");
    pqp_model_destroy(m);
    return differ ? 1 : 0;
}
